#version 330 core
// Polylines (render/passes/lines.py): each vertex to clip space, with its colour and its
// number (a segment's neighbour is its own end where it has none: lines.geom tells).
in vec3 in_position;
#ifdef LINE_COLORS
in vec3 in_color;
out vec3 v_color;
#endif
uniform mat4 u_model_view;
uniform mat4 u_proj;
flat out int v_index;

void main() {
    vec4 p = u_model_view * vec4(in_position, 1.0);
    v_index = gl_VertexID;
#ifdef LINE_COLORS
    v_color = in_color;
#endif
    gl_Position = u_proj * p;
}
