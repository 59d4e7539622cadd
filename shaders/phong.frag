#version 330 core
// Phong shading: normals interpolated, renormalised and lit at every pixel, with L and V
// per pixel.
#include "shadow_mask.glsl"
#include "lighting.glsl"
#include "surface.glsl"
#include "outputs.glsl"
#include "textures.glsl"

in vec3 v_position_view;
in vec3 v_normal_view;
#ifdef TEXTURED
in vec2 v_uv;
#endif
#ifdef VERTEX_COLORS
in vec4 v_color;
#endif
#ifdef PBR_NORMAL_MAP
in vec4 v_tangent_view;
#endif
#ifdef WORLD_NORMALS
in vec3 v_normal_world;
#endif

void main() {
    vec3 n = normalize(v_normal_view);
#ifdef PBR_NORMAL_MAP
    n = pbr_mapped_normal(n, v_tangent_view, v_uv);  // (before a back face turns it round)
#endif
#ifdef WORLD_NORMALS
    vec3 n_world = normalize(v_normal_world);
#else
    vec3 n_world = vec3(0.0, 0.0, 1.0);  // (not written: no normal output)
#endif
    face_viewer(n, n_world);
    SHADOW_PREPARE(v_position_view, n_world);
#ifdef VERTEX_COLORS
    g_surface_color = v_color.rgb;  // (the notes' C at this pixel: surface_color.glsl)
#endif
#ifdef PBR_TEXTURED
    g_pbr_uv = v_uv;  // (the maps at this pixel: pbr.glsl)
    g_map_opacity = pbr_map_alpha(v_uv);
#endif
#ifdef NOTES_TEXTURED
    vec3 specular;
    vec3 lit = light_parts(v_position_view, n, view_dir(v_position_view), specular);
    g_map_opacity = map_opacity(v_uv);
#ifdef VERTEX_COLORS
    g_map_opacity *= v_color.a;
#endif
    write_outputs(textured_color(lit, specular, v_uv), n_world, -v_position_view.z);
#else
#ifdef VERTEX_COLORS
    g_map_opacity *= v_color.a;
#endif
    write_outputs(light_intensity(v_position_view, n, view_dir(v_position_view)), n_world,
                  -v_position_view.z);
#endif
}
