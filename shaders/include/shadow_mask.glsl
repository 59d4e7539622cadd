// Cast shadows in a fragment stage: a shadow pass (render/passes/shadows.py) left, for
// this pixel's nearest surface point, how much of each light reaches it (1 seen, 0 hidden;
// a shadow map's PCF gives fractions), one layer of u_visibility per light. Include it
// before lighting.glsl: its LIGHT_VISIBLE weighs each light's term.
#ifndef SHADOW_MASK_GLSL
#define SHADOW_MASK_GLSL
#ifdef SHADOW_MASK
uniform sampler2DArray u_visibility;
#define LIGHT_VISIBLE(i) texelFetch(u_visibility, ivec3(ivec2(gl_FragCoord.xy), i), 0).r

// The ambient term and the terms of the lights this pixel's point sees (flat and Gouraud:
// the terms were made at the corners, light by light).
vec3 visible_sum(vec3 ambient, vec3 terms[LIGHT_COUNT]) {
    vec3 color = ambient;
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        color += LIGHT_VISIBLE(i) * terms[i];
    }
    return color;
}
#endif
#endif
