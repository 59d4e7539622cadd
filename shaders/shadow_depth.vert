#version 330 core
// A light's depth map (render/passes/shadow_maps.py): the scene's world triangles through
// one face's view and projection; depth only.
uniform mat4 u_mvp;
in vec3 in_position;

void main() {
    gl_Position = u_mvp * vec4(in_position, 1.0);
}
