#version 330 core
// Uniform (flat) shading: the polygon's normal, L and V taken at its centroid.
#include "lighting.glsl"
#include "outputs.glsl"

uniform bool u_orthographic;

flat in vec3 v_face_normal_view;
flat in vec3 v_face_normal_world;
flat in vec3 v_centroid_view;
in vec3 v_position_view;

void main() {
    vec3 n = normalize(v_face_normal_view);
    vec3 n_world = normalize(v_face_normal_world);
    if (!gl_FrontFacing) {
        n = -n;
        n_world = -n_world;
    }
    vec3 v = u_orthographic ? vec3(0.0, 0.0, 1.0) : normalize(-v_centroid_view);
    write_outputs(light_intensity(v_centroid_view, n, v), n_world, -v_position_view.z);
}
