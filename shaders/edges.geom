#version 330 core
// Each edge becomes a screen-aligned quad ``u_edge_width`` pixels wide. Every fragment
// carries the point of the edge's centre line it belongs to (window pixels) and the edge's
// depth there (NDC z, which is linear along the line on screen): edges.frag decides, per
// pixel, whether that point of the edge is seen.
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

uniform vec2 u_viewport_origin; // pixels
uniform vec2 u_viewport_size;   // pixels
uniform float u_edge_width;     // pixels

noperspective out vec2 g_centre;   // the centre line's point, window pixels
noperspective out float g_ndc_z;   // the edge's depth there

void emit(vec2 ndc, vec2 centre_ndc, float z) {
    g_centre = (centre_ndc * 0.5 + 0.5) * u_viewport_size + u_viewport_origin;
    g_ndc_z = z;
    gl_Position = vec4(ndc, 0.0, 1.0);
    EmitVertex();
}

void main() {
    vec4 a = gl_in[0].gl_Position, b = gl_in[1].gl_Position;
    // (an edge crossing the near plane is clipped to it first, here: w > 0 on both ends)
    float eps = 1e-5;
    if (a.w < eps && b.w < eps) return;
    if (a.w < eps) a = mix(a, b, (eps - a.w) / (b.w - a.w));
    if (b.w < eps) b = mix(b, a, (eps - b.w) / (a.w - b.w));
    vec2 na = a.xy / a.w, nb = b.xy / b.w;
    vec2 dir = (nb - na) * 0.5 * u_viewport_size;
    float len = length(dir);
    vec2 n = len > 0.0 ? vec2(-dir.y, dir.x) / len : vec2(1.0, 0.0);
    vec2 off = n * 0.5 * u_edge_width / (0.5 * u_viewport_size);
    float za = a.z / a.w, zb = b.z / b.w;
    emit(na + off, na, za);
    emit(na - off, na, za);
    emit(nb + off, nb, zb);
    emit(nb - off, nb, zb);
    EndPrimitive();
}
