#version 330 core
// A screen-aligned textured quad (labels drawn over the viewer's panes): the quad's corner
// in normalised device coordinates, and its texture coordinate.
in vec2 in_ndc;
in vec2 in_uv;
out vec2 v_uv;

void main() {
    v_uv = in_uv;
    gl_Position = vec4(in_ndc, 0.0, 1.0);
}
