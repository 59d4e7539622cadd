#version 330 core
// Uniform (flat) shading. Vertices are duplicated per triangle corner and carry their
// polygon's unit Newell normal and centroid, so every corner of a polygon -- a quad or an
// n-gon included -- computes the same N, L, R and V: one intensity per polygon, evaluated
// per corner (the notes: N, L, R, V are constant over the polygon), never per pixel, and
// passed on flat. Two-sided programs (TWO_SIDED: not culled) also light the back.
#include "polygon_id.glsl"
#include "transforms.glsl"
#include "lighting.glsl"

in vec3 in_position;
in vec3 in_face_normal;
in vec3 in_face_centroid;
#ifdef TEXTURED
in vec2 in_uv;
out vec2 v_uv;  // (per pixel: the polygon's one lit colour times its texels)
#ifdef SHADOW_MASK
flat out vec3 v_spec_terms_front[LIGHT_COUNT];  // (v_terms_*: ambient and diffuse)
#ifdef TWO_SIDED
flat out vec3 v_spec_terms_back[LIGHT_COUNT];
#endif
#else
flat out vec3 v_spec_front;
#ifdef TWO_SIDED
flat out vec3 v_spec_back;
#endif
#endif
#endif

flat out vec3 v_color_front;
#ifdef TWO_SIDED
flat out vec3 v_color_back;
#endif
#ifdef WORLD_NORMALS
flat out vec3 v_face_normal_world;
#endif
#ifdef SHADOW_MASK
flat out vec3 v_terms_front[LIGHT_COUNT];  // each light's term apart (v_color_*: ambient)
#ifdef TWO_SIDED
flat out vec3 v_terms_back[LIGHT_COUNT];
#endif
#endif
out vec3 v_position_view;

void main() {
    PASS_POLYGON_ID();
    vec4 p_view = u_model_view * vec4(in_position, 1.0);
    v_position_view = p_view.xyz;
    vec3 n = normalize(u_normal_view * in_face_normal);
    vec3 c = (u_model_view * vec4(in_face_centroid, 1.0)).xyz;
    vec3 v = view_dir(c);
#ifdef TEXTURED
    v_uv = in_uv;
#endif
#if defined(TEXTURED) && defined(SHADOW_MASK)
    vec3 terms[LIGHT_COUNT], spec_terms[LIGHT_COUNT];
    v_color_front = light_terms_parts(c, n, v, terms, spec_terms);
    v_terms_front = terms;
    v_spec_terms_front = spec_terms;
#ifdef TWO_SIDED
    v_color_back = light_terms_parts(c, -n, v, terms, spec_terms);
    v_terms_back = terms;
    v_spec_terms_back = spec_terms;
#endif
#elif defined(TEXTURED)
    v_color_front = light_parts(c, n, v, v_spec_front);
#ifdef TWO_SIDED
    v_color_back = light_parts(c, -n, v, v_spec_back);
#endif
#elif defined(SHADOW_MASK)
    vec3 terms[LIGHT_COUNT];
    v_color_front = light_terms(c, n, v, terms);
    v_terms_front = terms;
#ifdef TWO_SIDED
    v_color_back = light_terms(c, -n, v, terms);
    v_terms_back = terms;
#endif
#else
    v_color_front = light_intensity(c, n, v);
#ifdef TWO_SIDED
    v_color_back = light_intensity(c, -n, v);
#endif
#endif
#ifdef WORLD_NORMALS
    v_face_normal_world = u_normal_world * in_face_normal;
#endif
    gl_Position = u_proj * p_view;
}
