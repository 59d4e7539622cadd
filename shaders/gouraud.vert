#version 330 core
// Gouraud shading: the lighting formula is evaluated at the vertices; the rasterizer
// interpolates the intensities linearly across each triangle. Two-sided programs
// (TWO_SIDED: not culled) light both sides and the fragment stage picks the one facing the
// viewer; with back faces culled only the front is lit.
#include "transforms.glsl"
#include "lighting.glsl"

in vec3 in_position;
in vec3 in_normal;

out vec3 v_color_front;
#ifdef TWO_SIDED
out vec3 v_color_back;
#endif
out vec3 v_position_view;
#ifdef WORLD_NORMALS
out vec3 v_normal_world;
#endif

void main() {
    vec4 p_view = u_model_view * vec4(in_position, 1.0);
    vec3 n = normalize(u_normal_view * in_normal);
    vec3 v = view_dir(p_view.xyz);
    v_color_front = light_intensity(p_view.xyz, n, v);
#ifdef TWO_SIDED
    v_color_back = light_intensity(p_view.xyz, -n, v);
#endif
    v_position_view = p_view.xyz;
#ifdef WORLD_NORMALS
    v_normal_world = u_normal_world * in_normal;
#endif
    gl_Position = u_proj * p_view;
}
