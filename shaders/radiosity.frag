#version 330 core
// Radiosity display: interpolated vertex radiosities, unlit.
#include "surface.glsl"
#include "outputs.glsl"

in vec3 v_color;
in vec3 v_position_view;
#ifdef WORLD_NORMALS
in vec3 v_normal_world;
#endif

void main() {
    vec3 n_view = vec3(0.0);
#ifdef WORLD_NORMALS
    vec3 n_world = v_normal_world;
#else
    vec3 n_world = vec3(0.0, 0.0, 1.0);  // (not written: no normal output)
#endif
    face_viewer(n_view, n_world);
    write_outputs(v_color, n_world, -v_position_view.z);
}
