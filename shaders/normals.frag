#version 330 core
// Debug view: the world-space normal as colour, (n + 1) / 2.
#include "surface.glsl"
#include "outputs.glsl"

in vec3 v_position_view;
in vec3 v_normal_view;
#ifdef WORLD_NORMALS
in vec3 v_normal_world;
#endif

void main() {
    vec3 n_view = v_normal_view;
#ifdef WORLD_NORMALS
    vec3 n_world = normalize(v_normal_world);
#else
    vec3 n_world = vec3(0.0, 0.0, 1.0);  // (not written: no normal output)
#endif
    face_viewer(n_view, n_world);
    write_outputs(0.5 * n_world + 0.5, n_world, -v_position_view.z);
}
