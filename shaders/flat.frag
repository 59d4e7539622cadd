#version 330 core
// Uniform (flat) shading: the polygon's one intensity, computed at its corners (flat.vert).
#define LIT_IN flat in
#ifdef WORLD_NORMALS
flat in vec3 v_face_normal_world;
#define SURFACE_NORMAL_WORLD normalize(v_face_normal_world)
#endif
#include "vertex_lit.glsl"
