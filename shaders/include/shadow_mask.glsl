// Cast shadows in a fragment stage: a shadow pass (render/passes/shadows.py) left, for
// this pixel's nearest surface point, how much of each light reaches it (1 seen, 0 hidden;
// a shadow map's PCF gives fractions), one layer of u_visibility per light. Include it
// before lighting.glsl: its LIGHT_VISIBLE weighs each light's term.
#ifndef SHADOW_MASK_GLSL
#define SHADOW_MASK_GLSL
#ifdef SHADOW_MASK
#ifdef SHADOW_MAPS_FORWARD
// Without a visibility array: the fragment looks each light's shadow map up itself, once,
// at its own surface point (SHADOW_PREPARE, called by the program's main before lighting).
#define SHADOW_LIGHTS LIGHT_COUNT
#include "shadow_lookup.glsl"
uniform mat4 u_camera_to_world;
#define HAS_CAMERA_TO_WORLD
float g_visible[LIGHT_COUNT];

void shadow_prepare(vec3 p_view, vec3 n_world) {
    vec3 p = (u_camera_to_world * vec4(p_view, 1.0)).xyz;
    vec3 n = normalize(n_world);
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        g_visible[i] = map_visibility(i, p, n);
    }
}
#define SHADOW_PREPARE(p_view, n_world) shadow_prepare(p_view, n_world)
#define LIGHT_VISIBLE(i) g_visible[i]
#else
uniform sampler2DArray u_visibility;
#define LIGHT_VISIBLE(i) texelFetch(u_visibility, ivec3(ivec2(gl_FragCoord.xy), i), 0).r
#define SHADOW_PREPARE(p_view, n_world)
#endif

// The ambient term and the terms of the lights this pixel's point sees (flat and Gouraud:
// the terms were made at the corners, light by light).
vec3 visible_sum(vec3 ambient, vec3 terms[LIGHT_COUNT]) {
    vec3 color = ambient;
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        color += LIGHT_VISIBLE(i) * terms[i];
    }
    return color;
}
#else
#define SHADOW_PREPARE(p_view, n_world)
#endif
#endif
