#version 330 core
// Radiosity display: the solution's radiosity at each vertex (an area-weighted average of
// the patches around it), interpolated across triangles like Gouraud intensities. Nothing
// is lit here: the light transport was solved beforehand (glshade.radiosity).
#include "polygon_id.glsl"
#include "transforms.glsl"

in vec3 in_position;
in vec3 in_normal;
in vec3 in_color;

out vec3 v_color;
out vec3 v_position_view;
#ifdef WORLD_NORMALS
out vec3 v_normal_world;
#endif

void main() {
    PASS_POLYGON_ID();
    vec4 p_view = u_model_view * vec4(in_position, 1.0);
    v_color = in_color;
    v_position_view = p_view.xyz;
#ifdef WORLD_NORMALS
    v_normal_world = u_normal_world * in_normal;
#endif
    gl_Position = u_proj * p_view;
}
