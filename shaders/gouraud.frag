#version 330 core
// Gouraud shading: interpolated vertex intensities.
#define LIT_IN in
#ifdef WORLD_NORMALS
in vec3 v_normal_world;
#define SURFACE_NORMAL_WORLD v_normal_world
#endif
#include "vertex_lit.glsl"
