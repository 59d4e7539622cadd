#version 330 core
// The id of the patch seen through this pixel. A patch seen from behind hides what is
// beyond it but receives nothing (surfaces reflect from their front only).
flat in int v_patch;

layout(location = 0) out int frag_patch;

void main() {
    frag_patch = gl_FrontFacing ? v_patch : 0;
}
