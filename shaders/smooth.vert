#version 330 core
// Vertex stage of the per-pixel programs (phong, normals, depth): passes view-space
// position and normal on to be interpolated (and, for Phong on a software rasterizer, the
// lighting constants as flat values: constants.glsl).
#include "transforms.glsl"
#ifdef FLAT_CONSTANTS
#define FORWARD_CONSTANTS
#include "constants.glsl"
#endif

in vec3 in_position;
in vec3 in_normal;

out vec3 v_position_view;
out vec3 v_normal_view;
#ifdef WORLD_NORMALS
out vec3 v_normal_world;
#endif

void main() {
    vec4 p_view = u_model_view * vec4(in_position, 1.0);
    v_position_view = p_view.xyz;
    v_normal_view = u_normal_view * in_normal;
#ifdef WORLD_NORMALS
    v_normal_world = u_normal_world * in_normal;
#endif
#ifdef FLAT_CONSTANTS
    forward_constants();
#endif
    gl_Position = u_proj * p_view;
}
