#version 330 core
// Uniform (flat) shading. Vertices are duplicated per triangle corner and carry their
// polygon's unit Newell normal and centroid, so every pixel of a polygon -- a quad or an
// n-gon included -- is lit with the same N, L, R and V: one intensity, no seam along a
// triangulation diagonal.
#include "transforms.glsl"

in vec3 in_position;
in vec3 in_face_normal;
in vec3 in_face_centroid;

flat out vec3 v_face_normal_view;
flat out vec3 v_face_normal_world;
flat out vec3 v_centroid_view;
out vec3 v_position_view;

void main() {
    vec4 p_view = u_view * u_model * vec4(in_position, 1.0);
    v_position_view = p_view.xyz;
    v_face_normal_view = u_normal_view * in_face_normal;
    v_face_normal_world = u_normal_world * in_face_normal;
    v_centroid_view = (u_view * u_model * vec4(in_face_centroid, 1.0)).xyz;
    gl_Position = u_proj * p_view;
}
