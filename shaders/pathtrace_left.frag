#version 330 core
// The path tracer's pixels that have not finished their samples (u_target, and u_extra's
// more for this pixel, at most u_cap in this step of the run): each such pixel passes (an
// occlusion query counts them), each finished one is discarded.
// With several streams a pixel (pixel_blocks.glsl), each copy's share of those samples.
uniform sampler2D u_acc0;
uniform sampler2D u_extra;
uniform float u_target;
uniform float u_cap;
uniform vec2 u_size;

out vec4 out_color;

#include "pixel_blocks.glsl"

void main() {
    ivec2 at = ivec2(gl_FragCoord.xy);
    // (past the image: the tracer left its count above any target)
    int stream = min(image_of(at).y / int(u_size.y), u_streams - 1);
    float target = min(u_target + texelFetch(u_extra, at, 0).r, u_cap);
    if (texelFetch(u_acc0, at, 0).w >= stream_share(target, stream)) discard;
    out_color = vec4(1.0);
}
