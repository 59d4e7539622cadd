#version 330 core
// Debug view: distance along the view axis as grey, white at near, black at far.
#include "surface.glsl"
#include "outputs.glsl"

uniform vec2 u_depth_range;  // near, far of the shown range

in vec3 v_position_view;
in vec3 v_normal_view;
#ifdef WORLD_NORMALS
in vec3 v_normal_world;
#endif

void main() {
    float d = -v_position_view.z;
    float g = 1.0 - clamp((d - u_depth_range.x) / (u_depth_range.y - u_depth_range.x), 0.0, 1.0);
    vec3 n_view = v_normal_view;
#ifdef WORLD_NORMALS
    vec3 n_world = normalize(v_normal_world);
#else
    vec3 n_world = vec3(0.0, 0.0, 1.0);  // (not written: no normal output)
#endif
    face_viewer(n_view, n_world);
    write_outputs(vec3(g), n_world, d);
}
