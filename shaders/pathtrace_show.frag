#version 330 core
// The path tracer's picture so far, on screen: each pixel's mean (sum / count) times the
// exposure, clipped, sRGB-encoded if asked (the viewer's progressive mode); each read
// where the tracer keeps the pixel (pixel_blocks.glsl).
uniform sampler2D u_sum;
uniform float u_exposure;
uniform bool u_srgb;

out vec4 out_color;

#include "srgb.glsl"
#include "pixel_blocks.glsl"

void main() {
    vec4 s = texelFetch(u_sum, target_of(ivec2(gl_FragCoord.xy)), 0);
    vec3 c = clamp(s.rgb / max(s.a, 1.0) * u_exposure, 0.0, 1.0);
    if (u_srgb) {
        c = encode_srgb(c);
    }
    out_color = vec4(c, 1.0);
}
