#version 330 core
// CSG solids: the back faces of the solid's bounding box, so that every pixel the solid
// may cover runs the fragment program -- with the camera outside the box or inside it.
uniform mat4 u_view_proj;
in vec3 in_position;

void main() {
    gl_Position = u_view_proj * vec4(in_position, 1.0);
}
