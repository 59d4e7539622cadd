// Where the path tracer keeps a pixel (render/passes/pathtrace.py, LAYOUT_BLOCKS): its
// targets hold the image in 8x8 blocks, in raster order, u_blocks.y blocks a target row
// (the image has u_blocks.x a row), so each of llvmpipe's 64x64 tiles -- a thread's unit
// of work -- holds parts of the whole image, not one corner's.
// With u_streams > 1 each pixel is kept u_streams times, each a stream of its samples
// (sample k in stream k mod u_streams: a GPU with more cores than the picture has pixels
// gets work for them): the targets then hold a picture u_streams times as tall, stream j's
// copy of row y at row j H + y.
#ifndef PIXEL_BLOCKS_GLSL
#define PIXEL_BLOCKS_GLSL
uniform ivec2 u_blocks;  // (the image's blocks a row, the target's)
uniform int u_streams;   // copies of each pixel, each a stream of its samples

// how many of a pixel's first n samples (a whole number) fall in stream j
float stream_share(float n, int j) {
    return max(floor((n - float(j) + float(u_streams) - 1.0) / float(u_streams)), 0.0);
}

// the image pixel a target pixel holds (past the image's edge where none)
ivec2 image_of(ivec2 t) {
    int b = (t.y / 8) * u_blocks.y + t.x / 8;
    return ivec2((b % u_blocks.x) * 8 + t.x % 8, (b / u_blocks.x) * 8 + t.y % 8);
}

// the target pixel that holds image pixel p
ivec2 target_of(ivec2 p) {
    int b = (p.y / 8) * u_blocks.x + p.x / 8;
    return ivec2((b % u_blocks.y) * 8 + p.x % 8, (b / u_blocks.y) * 8 + p.y % 8);
}
#endif
