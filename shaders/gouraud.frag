#version 330 core
// Gouraud shading: interpolated vertex intensities.
#include "outputs.glsl"

in vec3 v_color_front;
in vec3 v_color_back;
in vec3 v_position_view;
in vec3 v_normal_world;

void main() {
    vec3 n_world = gl_FrontFacing ? v_normal_world : -v_normal_world;
    vec3 color = gl_FrontFacing ? v_color_front : v_color_back;
    write_outputs(color, n_world, -v_position_view.z);
}
