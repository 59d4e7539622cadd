#version 330 core
// Each edge becomes a screen-aligned quad ``u_edge_width`` pixels wide. Every fragment
// carries the point of the edge's centre line it belongs to (window pixels), the edge's
// depth there (NDC z, which is linear along the line on screen) and the planes of the
// edge's two faces (view space): edges.frag decides, per pixel, whether that point of the
// edge is seen.
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;

uniform vec2 u_viewport_origin; // pixels
uniform vec2 u_viewport_size;   // pixels
uniform float u_edge_width;     // pixels

in vec3 v_position[];
in vec3 v_normal_a[];
in vec3 v_normal_b[];

noperspective out vec2 g_centre;   // the centre line's point, window pixels
noperspective out float g_ndc_z;   // the edge's depth there
flat out vec4 g_plane_a;           // (n, n . p) of the edge's faces, view space
flat out vec4 g_plane_b;

void emit(vec2 ndc, vec2 centre_ndc, float z, vec4 plane_a, vec4 plane_b) {
    g_centre = (centre_ndc * 0.5 + 0.5) * u_viewport_size + u_viewport_origin;
    g_ndc_z = z;
    g_plane_a = plane_a;
    g_plane_b = plane_b;
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
    vec3 p = v_position[0];
    vec4 pa = vec4(v_normal_a[0], dot(v_normal_a[0], p));
    vec4 pb = vec4(v_normal_b[0], dot(v_normal_b[0], p));
    emit(na + off, na, za, pa, pb);
    emit(na - off, na, za, pa, pb);
    emit(nb + off, nb, zb, pa, pb);
    emit(nb - off, nb, zb, pa, pb);
    EndPrimitive();
}
