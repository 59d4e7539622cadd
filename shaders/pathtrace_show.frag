#version 330 core
// The path tracer's picture so far, on screen: each pixel's mean (sum / count) times the
// exposure, clipped, sRGB-encoded if asked (the viewer's progressive mode); each read
// where the tracer keeps the pixel (pixel_blocks.glsl).
uniform sampler2D u_sum;
uniform float u_exposure;
uniform bool u_srgb;
uniform vec2 u_size;

out vec4 out_color;

#include "srgb.glsl"
#include "pixel_blocks.glsl"

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 s = vec4(0.0);
    for (int j = 0; j < u_streams; ++j) {  // (the pixel's streams, each its share)
        s += texelFetch(u_sum, target_of(p + ivec2(0, j * int(u_size.y))), 0);
    }
    vec3 c = clamp(s.rgb / max(s.a, 1.0) * u_exposure, 0.0, 1.0);
    if (u_srgb) {
        c = encode_srgb(c);
    }
    out_color = vec4(c, 1.0);
}
