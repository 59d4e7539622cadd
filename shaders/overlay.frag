#version 330 core
// Draws a premultiplied-alpha RGBA image (text rendered by Pillow) over what is there.
uniform sampler2D u_image;
in vec2 v_uv;
out vec4 frag_color;

void main() {
    frag_color = texture(u_image, v_uv);
}
