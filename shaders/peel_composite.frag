#version 330 core
// Depth peeling's last step (render/passes/peeling.py): the peeled layers, accumulated
// front to back as premultiplied colour C and transmittance T, over a float copy of the
// opaque picture -- out = C + T behind, in one rounding, the picture's alpha kept (its
// coverage): what the fragment lists' resolve (oit_resolve.frag) writes.
uniform sampler2D u_accum;
uniform sampler2D u_behind;
out vec4 frag_color;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    vec4 acc = texelFetch(u_accum, px, 0);
    if (acc.a == 1.0 && acc.rgb == vec3(0.0)) discard;  // (no layer here)
    vec4 behind = texelFetch(u_behind, px, 0);
    frag_color = vec4(acc.rgb + acc.a * behind.rgb, behind.a);
}
