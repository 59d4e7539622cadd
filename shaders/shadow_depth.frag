#version 330 core
// Depth only: the z-buffer keeps the nearest occluder of each texel.
void main() {
}
