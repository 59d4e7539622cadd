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
out vec3 v_position_view;
#ifdef WORLD_NORMALS
out vec3 v_normal_world;
#endif

void gouraud_stage(vec3 position, vec3 normal) {
    vec4 p_view = u_model_view * vec4(position, 1.0);
    vec3 n = normalize(u_normal_view * normal);
    vec3 v = view_dir(p_view.xyz);
#ifdef SHADOW_MASK
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
