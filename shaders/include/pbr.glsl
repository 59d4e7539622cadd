// glTF 2.0's metallic-roughness lighting model (scene/pbr.py PBRMaterial), the BRDF of the
// glTF 2.0 specification's Appendix B, in one place for every program that lights it
// (included by lighting.glsl in place of the notes' formula when a program is compiled
// PBR: flat, Gouraud and Phong evaluate it where they evaluate the notes' model):
//   f = (1 - F) (1 - metallic) base / pi + F D V,
//   F = F0 + (1 - F0) (1 - V.H)^5,  F0 = mix(0.04, base, metallic)          (Schlick)
//   D = a^2 / (pi ((N.H)^2 (a^2 - 1) + 1)^2),  a = roughness^2         (Trowbridge-Reitz)
//   V = 0.5 / (N.L sqrt((N.V)^2 (1 - a^2) + a^2) + N.V sqrt((N.L)^2 (1 - a^2) + a^2))
//                                                          (height-correlated Smith)
// and each light adds f x its colour x intensity x N.L, the intensity over d^2 for point and
// spot lights (candela), as it is for directional ones (lux); nothing from behind the
// surface. The light's colour x intensity arrives as LIGHT_SPECULAR(i) (constants.glsl),
// the scene's ambient light x ka x the base colour as AMBIENT_TERM (glTF has none: the
// notes' coefficient). Its numpy twin:
// cpu/lighting.py (pbr_radiance).
#ifndef PBR_GLSL
#define PBR_GLSL
#include "pbr_brdf.glsl"
#ifdef ENVIRONMENT_LIGHT
#include "environment_light.glsl"
#endif

uniform vec4 u_pbr_base;        // base colour (linear RGB), metallic
uniform float u_pbr_roughness;  // perceptual roughness
#ifdef PBR_TEXTURED
#include "textures.glsl"
uniform vec3 u_emission;        // the emissive factor (x its map: added here, not outputs')
vec2 g_pbr_uv = vec2(0.0);      // where the maps are read: set by the stage that lights
#endif

// The base colour at the point lit: the material's times the mesh's (surface_color.glsl)
// times its map's.
vec3 pbr_base_color() {
    vec3 base = u_pbr_base.rgb;
#ifdef VERTEX_COLORS
    base *= SURFACE_C;
#endif
#ifdef PBR_TEXTURED
    base *= texture(u_pbr_base_map, g_pbr_uv).rgb;
#endif
    return base;
}

float pbr_metallic() {
#ifdef PBR_TEXTURED
    return u_pbr_base.a * texture(u_pbr_mr_map, g_pbr_uv).b;
#else
    return u_pbr_base.a;
#endif
}

float pbr_roughness() {
#ifdef PBR_TEXTURED
    return u_pbr_roughness * texture(u_pbr_mr_map, g_pbr_uv).g;
#else
    return u_pbr_roughness;
#endif
}

// The ambient light x the base colour and, with ENVIRONMENT_LIGHT, the sky's light
// (environment_light.glsl) -- glTF's indirect light, both x the occlusion map's -- and with
// maps the emission (its factor x its map: without maps outputs.glsl adds the factor).
vec3 pbr_ambient(vec3 n_view, vec3 v_view) {
    vec3 indirect = AMBIENT_TERM;
#ifdef PBR_TEXTURED
    indirect *= texture(u_pbr_base_map, g_pbr_uv).rgb;
#endif
#ifdef ENVIRONMENT_LIGHT
    indirect += environment_light(n_view, v_view, pbr_base_color(), pbr_metallic(),
                                  pbr_roughness());
#endif
#ifdef PBR_TEXTURED
    return indirect * texture(u_pbr_occlusion_map, g_pbr_uv).r +
           u_emission * texture(u_pbr_emissive_map, g_pbr_uv).rgb;
#else
    return indirect;
#endif
}

// One light's term: f x colour x intensity (/ d^2, x a spot's cone) x N.L.
vec3 light_term(int i, int kind, vec3 p_view, vec3 n_view, vec3 v_view) {
    vec3 l = LIGHT_POS_VIEW(i).xyz;
    float k = 1.0;
    if (kind != DIRECTIONAL) {
        vec3 to_light = l - p_view;
        float d2 = max(dot(to_light, to_light), 1e-30);
        l = to_light * inversesqrt(d2);
        k = range_window(sqrt(d2), LIGHT_POS_VIEW(i).w) / d2;
        if (kind == SPOT) {  // (KHR_lights_punctual's cone, as for the notes' model)
            vec4 spot = LIGHT_SPOT(i);
            float s = clamp(dot(spot.xyz, -l) + spot.w, 0.0, 1.0);
            k *= s * s;
        }
    }
    return k * LIGHT_SPECULAR(i) *
           pbr_brdf_cos(n_view, l, v_view, pbr_base_color(), pbr_metallic(), pbr_roughness());
}
#endif
