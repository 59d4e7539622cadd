#version 400 core
// Every patch at one uniform level (u_level segments a side, inner and outer alike), so
// neighbours share their edges' samples: the same crack-free grid the CPU tessellates.
layout(vertices = PATCH_POINTS) out;

uniform float u_level;
in vec4 c_control[];
out vec4 e_control[];

void main() {
    e_control[gl_InvocationID] = c_control[gl_InvocationID];
    if (gl_InvocationID == 0) {
        gl_TessLevelOuter[0] = u_level;
        gl_TessLevelOuter[1] = u_level;
        gl_TessLevelOuter[2] = u_level;
        gl_TessLevelOuter[3] = u_level;
        gl_TessLevelInner[0] = u_level;
        gl_TessLevelInner[1] = u_level;
    }
}
