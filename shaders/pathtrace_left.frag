#version 330 core
// The path tracer's pixels that have not finished u_target samples: each such pixel passes
// (an occlusion query counts them), each finished one is discarded.
uniform sampler2D u_acc0;
uniform float u_target;

out vec4 out_color;

void main() {
    if (texelFetch(u_acc0, ivec2(gl_FragCoord.xy), 0).w >= u_target) discard;
    out_color = vec4(1.0);
}
