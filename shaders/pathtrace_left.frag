#version 330 core
// The path tracer's pixels that have not finished their samples (u_target, and u_extra's
// more for this pixel, at most u_cap in this step of the run): each such pixel passes (an
// occlusion query counts them), each finished one is discarded.
uniform sampler2D u_acc0;
uniform sampler2D u_extra;
uniform float u_target;
uniform float u_cap;

out vec4 out_color;

void main() {
    if (texelFetch(u_acc0, ivec2(gl_FragCoord.xy), 0).w
        >= min(u_target + texelFetch(u_extra, ivec2(gl_FragCoord.xy), 0).r, u_cap)) discard;
    out_color = vec4(1.0);
}
