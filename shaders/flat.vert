#version 330 core
// Uniform (flat) shading. Vertices are duplicated per triangle corner and carry their
// polygon's unit Newell normal and centroid, so every corner of a polygon -- a quad or an
// n-gon included -- computes the same N, L, R and V: one intensity per polygon, evaluated
// per corner (flat_polygon.glsl), never per pixel, and passed on flat. A big mesh's draw
// (FLAT_FETCH) shares its vertices instead: this stage places them, flat.geom lights each
// triangle's polygon.
#include "polygon_id.glsl"
#include "transforms.glsl"
#include "lighting.glsl"

in vec3 in_position;
#ifdef FLAT_FETCH
#ifdef TEXTURED
in vec2 in_uv;
out vec2 g_uv;
#endif
out vec3 g_position_view;

void main() {
    vec4 p_view = u_model_view * vec4(in_position, 1.0);
    g_position_view = p_view.xyz;
#ifdef TEXTURED
    g_uv = in_uv;
#endif
    gl_Position = u_proj * p_view;
}
#else
#include "flat_polygon.glsl"
in vec3 in_face_normal;
in vec3 in_face_centroid;
#ifdef TEXTURED
in vec2 in_uv;
out vec2 v_uv;  // (per pixel: the polygon's one lit colour times its texels)
#endif
#ifdef PBR_TEXTURED
in vec2 in_face_uv;  // (the mean of the polygon's corners' uv: gpu_mesh.py)
#endif
#ifdef PBR_NORMAL_MAP
in vec4 in_face_tangent;  // (the polygon's tangent frame: the map bends its normal)
#endif
#ifdef VERTEX_COLORS
in vec4 in_color;  // (the polygon's one colour at each of its corners: gpu_mesh.py)
flat out float v_alpha;
#endif
out vec3 v_position_view;

void main() {
    PASS_POLYGON_ID();
    vec4 p_view = u_model_view * vec4(in_position, 1.0);
    v_position_view = p_view.xyz;
#ifdef TEXTURED
    v_uv = in_uv;
#endif
#ifdef VERTEX_COLORS
    g_surface_color = in_color.rgb;
    v_alpha = in_color.a;
#endif
#ifdef PBR_TEXTURED
    g_pbr_uv = in_face_uv;  // (glTF's maps read once, at the polygon's centre)
#endif
#ifdef PBR_NORMAL_MAP
    flat_polygon(pbr_mapped_normal(normalize(in_face_normal), in_face_tangent, in_face_uv),
                 in_face_centroid);
#else
    flat_polygon(in_face_normal, in_face_centroid);
#endif
    gl_Position = u_proj * p_view;
}
#endif
