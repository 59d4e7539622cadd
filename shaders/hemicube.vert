#version 330 core
// Hemicube faces for radiosity form factors: world positions straight through one
// face's view-projection; every corner carries its patch's id (id + 1; 0 = nothing).
uniform mat4 u_view_proj;

in vec3 in_position;
in int in_patch;

flat out int v_patch;

void main() {
    v_patch = in_patch;
    gl_Position = u_view_proj * vec4(in_position, 1.0);
}
