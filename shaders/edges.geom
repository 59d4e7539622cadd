#version 330 core
// Each edge becomes a screen-aligned quad ``u_edge_width`` pixels wide (wide_lines.glsl,
// the polylines' construction). Every fragment
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

#include "wide_lines.glsl"

void emit(vec2 window, vec2 centre, float z, vec4 plane_a, vec4 plane_b) {
    g_centre = centre;
    g_ndc_z = z;
    g_plane_a = plane_a;
    g_plane_b = plane_b;
    gl_Position = vec4(to_ndc(window, u_viewport_origin, u_viewport_size), 0.0, 1.0);
    EmitVertex();
}

void main() {
    vec4 a = gl_in[0].gl_Position, b = gl_in[1].gl_Position;
    if (!clip_near(a, b)) return;  // (an edge crossing the near plane: cut there)
    vec2 wa = to_window(a, u_viewport_origin, u_viewport_size);
    vec2 wb = to_window(b, u_viewport_origin, u_viewport_size);
    vec2 corners[4];
    segment_quad(wa, wb, 0.5 * u_edge_width, 0.0, 0.0, corners);
    float za = a.z / a.w, zb = b.z / b.w;
    vec3 p = v_position[0];
    vec4 pa = vec4(v_normal_a[0], dot(v_normal_a[0], p));
    vec4 pb = vec4(v_normal_b[0], dot(v_normal_b[0], p));
    emit(corners[0], wa, za, pa, pb);
    emit(corners[1], wa, za, pa, pb);
    emit(corners[2], wb, zb, pa, pb);
    emit(corners[3], wb, zb, pa, pb);
    EndPrimitive();
}
