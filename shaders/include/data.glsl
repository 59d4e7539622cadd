// Float tables in an RGBA32F texture, ``width`` texels a row, read whole (texelFetch): the
// one layout render/data.py's data_texture uploads.
#ifndef DATA_GLSL
#define DATA_GLSL
vec4 data_texel(sampler2D table, int i, int width) {
    return texelFetch(table, ivec2(i % width, i / width), 0);
}
#endif
