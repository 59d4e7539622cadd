#version 330 core
// Gouraud shading: interpolated vertex intensities.
#include "surface.glsl"
#include "outputs.glsl"

in vec3 v_color_front;
#ifdef TWO_SIDED
in vec3 v_color_back;
#endif
in vec3 v_position_view;
in vec3 v_normal_world;

void main() {
    vec3 n_view = vec3(0.0);  // (lighting was done per vertex)
    vec3 n_world = v_normal_world;
    face_viewer(n_view, n_world);
#ifdef TWO_SIDED
    vec3 color = gl_FrontFacing ? v_color_front : v_color_back;
#else
    vec3 color = v_color_front;  // back faces are culled
#endif
    write_outputs(color, n_world, -v_position_view.z);
}
