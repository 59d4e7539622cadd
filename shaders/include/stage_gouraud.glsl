// Gouraud's vertex work for one vertex (``position``, ``normal`` in model space): the
// lighting formula evaluated there, front (and with TWO_SIDED back) intensities out, to be
// interpolated linearly. gouraud.vert calls it per mesh vertex, patch.tese per tessellated
// vertex.
#include "transforms.glsl"
#include "lighting.glsl"

out vec3 v_color_front;
#ifdef TWO_SIDED
out vec3 v_color_back;
#endif
#ifdef SHADOW_MASK
out vec3 v_terms_front[LIGHT_COUNT];  // each light's term apart (v_color_*: the ambient)
#ifdef TWO_SIDED
out vec3 v_terms_back[LIGHT_COUNT];
#endif
#endif
#ifdef NOTES_TEXTURED
// textured: v_color_* and v_terms_* hold ambient and diffuse, these the specular terms
#ifdef SHADOW_MASK
out vec3 v_spec_terms_front[LIGHT_COUNT];
#ifdef TWO_SIDED
out vec3 v_spec_terms_back[LIGHT_COUNT];
#endif
#else
out vec3 v_spec_front;
#ifdef TWO_SIDED
out vec3 v_spec_back;
#endif
#endif
#endif
out vec3 v_position_view;
#ifdef WORLD_NORMALS
out vec3 v_normal_world;
#endif

void gouraud_stage(vec3 position, vec3 normal) {
    vec4 p_view = u_model_view * vec4(position, 1.0);
    vec3 n = normalize(u_normal_view * normal);
    vec3 v = view_dir(p_view.xyz);
#if defined(NOTES_TEXTURED) && defined(SHADOW_MASK)
    vec3 terms[LIGHT_COUNT], spec_terms[LIGHT_COUNT];
    v_color_front = light_terms_parts(p_view.xyz, n, v, terms, spec_terms);
    v_terms_front = terms;
    v_spec_terms_front = spec_terms;
#ifdef TWO_SIDED
    v_color_back = light_terms_parts(p_view.xyz, -n, v, terms, spec_terms);
    v_terms_back = terms;
    v_spec_terms_back = spec_terms;
#endif
#elif defined(NOTES_TEXTURED)
    v_color_front = light_parts(p_view.xyz, n, v, v_spec_front);
#ifdef TWO_SIDED
    v_color_back = light_parts(p_view.xyz, -n, v, v_spec_back);
#endif
#elif defined(SHADOW_MASK)
    vec3 terms[LIGHT_COUNT];
    v_color_front = light_terms(p_view.xyz, n, v, terms);
    v_terms_front = terms;
#ifdef TWO_SIDED
    v_color_back = light_terms(p_view.xyz, -n, v, terms);
    v_terms_back = terms;
#endif
#else
    v_color_front = light_intensity(p_view.xyz, n, v);
#ifdef TWO_SIDED
    v_color_back = light_intensity(p_view.xyz, -n, v);
#endif
#endif
    v_position_view = p_view.xyz;
#ifdef WORLD_NORMALS
    v_normal_world = u_normal_world * normal;
#endif
    gl_Position = u_proj * p_view;
}
