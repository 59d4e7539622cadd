#version 330 core
// The id of the patch seen through this pixel (1..P). A patch seen from behind hides what
// is beyond it but receives nothing (surfaces reflect from their front only): it reads as
// u_back_id (P + 1), so the share of a point's hemicube that meets back faces is known.
flat in int v_patch;
uniform int u_back_id;

layout(location = 0) out int frag_patch;

void main() {
    frag_patch = gl_FrontFacing ? v_patch : u_back_id;
}
