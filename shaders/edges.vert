#version 330 core
// Polygon edges (the boundaries of the mesh's polygons, never its triangulation's
// diagonals): one line per edge, widened on screen by edges.geom. Each end carries the unit
// normals of the edge's two faces, turned into view space: with the end's position they
// are the faces' planes, which edges.frag looks for in the depth buffer.
#include "transforms.glsl"

in vec3 in_position;
in vec3 in_normal_a;
in vec3 in_normal_b;

out vec3 v_position;   // view space
out vec3 v_normal_a;   // view space (zero for a degenerate face)
out vec3 v_normal_b;

void main() {
    vec4 p = u_model_view * vec4(in_position, 1.0);
    v_position = p.xyz;
    v_normal_a = u_normal_view * in_normal_a;
    v_normal_b = u_normal_view * in_normal_b;
    gl_Position = u_proj * p;
}
