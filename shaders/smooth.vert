#version 330 core
// Vertex stage of the per-pixel programs (phong, normals, depth): passes view-space
// position and normal on to be interpolated (and, for Phong on a software rasterizer, the
// lighting constants as flat values: constants.glsl).
#include "polygon_id.glsl"
#include "stage_smooth.glsl"
#ifdef FLAT_CONSTANTS
#define FORWARD_CONSTANTS
#include "constants.glsl"
#endif

in vec3 in_position;
in vec3 in_normal;
#ifdef TEXTURED
in vec2 in_uv;
out vec2 v_uv;  // (interpolated perspective-correct)
#endif
#ifdef VERTEX_COLORS
in vec4 in_color;
out vec4 v_color;  // (the mesh's C and alpha, interpolated: lit per pixel)
#endif
#ifdef PBR_NORMAL_MAP
in vec4 in_tangent;
out vec4 v_tangent_view;  // (the tangent frame in view space, interpolated: mapped per pixel)
#endif

void main() {
    PASS_POLYGON_ID();
    smooth_stage(in_position, in_normal);
#ifdef TEXTURED
    v_uv = in_uv;
#endif
#ifdef VERTEX_COLORS
    v_color = in_color;
#endif
#ifdef PBR_NORMAL_MAP
    v_tangent_view = vec4(mat3(u_model_view) * in_tangent.xyz, in_tangent.w);
#endif
#ifdef FLAT_CONSTANTS
    forward_constants();
#endif
}
