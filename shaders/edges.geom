#version 330 core
// Each edge becomes a screen-aligned quad ``u_edge_width`` pixels wide, drawn a little in
// front of the surface it lies on (so the z-buffer keeps it, and hides the edges behind).
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

uniform vec2 u_viewport_size;  // pixels
uniform float u_edge_width;    // pixels
uniform float u_edge_bias;     // of normalised depth, towards the eye

void main() {
    vec4 a = gl_in[0].gl_Position, b = gl_in[1].gl_Position;
    // (an edge crossing the near plane is clipped to it first, here: w > 0 on both ends)
    float eps = 1e-5;
    if (a.w < eps && b.w < eps) return;
    if (a.w < eps) a = mix(a, b, (eps - a.w) / (b.w - a.w));
    if (b.w < eps) b = mix(b, a, (eps - b.w) / (a.w - b.w));
    vec2 sa = a.xy / a.w * 0.5 * u_viewport_size, sb = b.xy / b.w * 0.5 * u_viewport_size;
    vec2 dir = sb - sa;
    float len = length(dir);
    vec2 n = len > 0.0 ? vec2(-dir.y, dir.x) / len : vec2(1.0, 0.0);
    vec2 off = n * 0.5 * u_edge_width / (0.5 * u_viewport_size);
    float za = a.z / a.w - u_edge_bias, zb = b.z / b.w - u_edge_bias;
    gl_Position = vec4(a.xy / a.w + off, za, 1.0); EmitVertex();
    gl_Position = vec4(a.xy / a.w - off, za, 1.0); EmitVertex();
    gl_Position = vec4(b.xy / b.w + off, zb, 1.0); EmitVertex();
    gl_Position = vec4(b.xy / b.w - off, zb, 1.0); EmitVertex();
    EndPrimitive();
}
