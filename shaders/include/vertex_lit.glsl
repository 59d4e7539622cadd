// The fragment stage of the modes lit in the vertex stage -- Gouraud (intensities at the
// vertices, interpolated) and flat (one intensity a polygon, computed at its corners) --
// which differ only in how the lit values arrive: the including file defines LIT_IN as
// "in" (interpolated) or "flat in" (the provoking vertex's), declares its world normal and
// names it SURFACE_NORMAL_WORLD (under WORLD_NORMALS).
#include "surface.glsl"
#include "shadow_mask.glsl"
#include "outputs.glsl"
#include "textures.glsl"

LIT_IN vec3 v_color_front;
#ifdef TWO_SIDED
LIT_IN vec3 v_color_back;
#endif
#ifdef SHADOW_MASK
LIT_IN vec3 v_terms_front[LIGHT_COUNT];
#ifdef TWO_SIDED
LIT_IN vec3 v_terms_back[LIGHT_COUNT];
#endif
#endif
#ifdef TEXTURED
in vec2 v_uv;
#endif
#ifdef NOTES_TEXTURED
#ifdef SHADOW_MASK
LIT_IN vec3 v_spec_terms_front[LIGHT_COUNT];
#ifdef TWO_SIDED
LIT_IN vec3 v_spec_terms_back[LIGHT_COUNT];
#endif
#else
LIT_IN vec3 v_spec_front;
#ifdef TWO_SIDED
LIT_IN vec3 v_spec_back;
#endif
#endif
#endif
#ifdef VERTEX_COLORS
LIT_IN float v_alpha;  // (the mesh colour's alpha: multiplies the opacity)
#endif
in vec3 v_position_view;

void main() {
    vec3 n_view = vec3(0.0);  // (lit in the vertex stage: per vertex, or per polygon)
#ifdef WORLD_NORMALS
    vec3 n_world = SURFACE_NORMAL_WORLD;
#else
    vec3 n_world = vec3(0.0, 0.0, 1.0);  // (not written: no normal output)
#endif
    face_viewer(n_view, n_world);
    SHADOW_PREPARE(v_position_view, n_world);
#ifdef TWO_SIDED
#ifdef SHADOW_MASK
    vec3 color = gl_FrontFacing ? visible_sum(v_color_front, v_terms_front)
                                : visible_sum(v_color_back, v_terms_back);
#else
    vec3 color = gl_FrontFacing ? v_color_front : v_color_back;
#endif
#elif defined(SHADOW_MASK)
    vec3 color = visible_sum(v_color_front, v_terms_front);
#else
    vec3 color = v_color_front;  // back faces are culled
#endif
#ifdef NOTES_TEXTURED
    // (the lit colour interpolated, its maps sampled per pixel)
#if defined(SHADOW_MASK) && defined(TWO_SIDED)
    vec3 specular = gl_FrontFacing ? visible_sum(vec3(0.0), v_spec_terms_front)
                                   : visible_sum(vec3(0.0), v_spec_terms_back);
#elif defined(SHADOW_MASK)
    vec3 specular = visible_sum(vec3(0.0), v_spec_terms_front);
#elif defined(TWO_SIDED)
    vec3 specular = gl_FrontFacing ? v_spec_front : v_spec_back;
#else
    vec3 specular = v_spec_front;
#endif
    color = textured_color(color, specular, v_uv);
    g_map_opacity = map_opacity(v_uv);
#elif defined(PBR_TEXTURED)
    g_map_opacity = pbr_map_alpha(v_uv);  // (lit where the scheme lights: the alpha per pixel)
#endif
#ifdef VERTEX_COLORS
    g_map_opacity *= v_alpha;
#endif
    write_outputs(color, n_world, -v_position_view.z);
}
