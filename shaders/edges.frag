#version 330 core
// An edge's colour, unlit.
uniform vec3 u_edge_color;
layout(location = 0) out vec4 frag_color;

void main() {
    frag_color = vec4(u_edge_color, 1.0);
}
