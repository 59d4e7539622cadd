#version 330 core
// Phong shading: normals interpolated, renormalised and lit at every pixel, with L and V
// per pixel.
#include "lighting.glsl"
#include "outputs.glsl"

uniform bool u_orthographic;

in vec3 v_position_view;
in vec3 v_normal_view;
in vec3 v_normal_world;

void main() {
    vec3 n = normalize(v_normal_view);
    vec3 n_world = normalize(v_normal_world);
    if (!gl_FrontFacing) {  // two-sided lighting: the back of a surface faces the viewer
        n = -n;
        n_world = -n_world;
    }
    vec3 v = u_orthographic ? vec3(0.0, 0.0, 1.0) : normalize(-v_position_view);
    write_outputs(light_intensity(v_position_view, n, v), n_world, -v_position_view.z);
}
