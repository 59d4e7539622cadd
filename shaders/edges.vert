#version 330 core
// Polygon edges (the boundaries of the mesh's polygons, never its triangulation's
// diagonals): one line per edge, widened on screen by edges.geom.
#include "transforms.glsl"

in vec3 in_position;

void main() {
    gl_Position = u_proj * (u_model_view * vec4(in_position, 1.0));
}
