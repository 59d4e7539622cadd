// The vertex work of the per-pixel programs (phong, normals, depth) for one vertex,
// ``position`` and ``normal`` in model space: view-space position and normal out, to be
// interpolated. smooth.vert calls it per mesh vertex, patch.tese per tessellated vertex.
#include "transforms.glsl"

out vec3 v_position_view;
out vec3 v_normal_view;
#ifdef WORLD_NORMALS
out vec3 v_normal_world;
#endif

void smooth_stage(vec3 position, vec3 normal) {
    vec4 p_view = u_model_view * vec4(position, 1.0);
    v_position_view = p_view.xyz;
    v_normal_view = u_normal_view * normal;
#ifdef WORLD_NORMALS
    v_normal_world = u_normal_world * normal;
#endif
    gl_Position = u_proj * p_view;
}
