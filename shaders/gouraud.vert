#version 330 core
// Gouraud shading: the lighting formula is evaluated at the vertices; the rasterizer
// interpolates the intensities linearly across each triangle. Two-sided programs
// (TWO_SIDED: not culled) light both sides and the fragment stage picks the one facing the
// viewer; with back faces culled only the front is lit.
#include "polygon_id.glsl"
#include "stage_gouraud.glsl"

in vec3 in_position;
in vec3 in_normal;
#ifdef TEXTURED
in vec2 in_uv;
out vec2 v_uv;
#endif
#ifdef VERTEX_COLORS
in vec4 in_color;
out float v_alpha;
#endif
#ifdef PBR_NORMAL_MAP
in vec4 in_tangent;  // (the map bends the vertex's normal, in model space)
#endif

void main() {
    PASS_POLYGON_ID();
#ifdef VERTEX_COLORS
    g_surface_color = in_color.rgb;  // (lit at the vertex with its own C)
    v_alpha = in_color.a;
#endif
#ifdef PBR_TEXTURED
    g_pbr_uv = in_uv;  // (glTF's maps read at the vertex: where Gouraud lights)
#endif
#ifdef PBR_NORMAL_MAP
    gouraud_stage(in_position, pbr_mapped_normal(normalize(in_normal), in_tangent, in_uv));
#else
    gouraud_stage(in_position, in_normal);
#endif
#ifdef TEXTURED
    v_uv = in_uv;
#endif
}
