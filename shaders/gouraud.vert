#version 330 core
// Gouraud shading: the lighting formula is evaluated at the vertices; the rasterizer
// interpolates the intensities linearly across each triangle. Two-sided programs
// (TWO_SIDED: not culled) light both sides and the fragment stage picks the one facing the
// viewer; with back faces culled only the front is lit.
#include "stage_gouraud.glsl"

in vec3 in_position;
in vec3 in_normal;

void main() {
    gouraud_stage(in_position, in_normal);
}
