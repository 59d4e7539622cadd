#version 330 core
// Uniform (flat) shading: the polygon's normal, L and V taken at its centroid.
#include "lighting.glsl"
#include "surface.glsl"
#include "outputs.glsl"

flat in vec3 v_face_normal_view;
flat in vec3 v_face_normal_world;
flat in vec3 v_centroid_view;
in vec3 v_position_view;

void main() {
    vec3 n = normalize(v_face_normal_view);
    vec3 n_world = normalize(v_face_normal_world);
    face_viewer(n, n_world);
    write_outputs(light_intensity(v_centroid_view, n, view_dir(v_centroid_view)), n_world,
                  -v_position_view.z);
}
