// The lighting model of the course notes, in one place for every program:
//   I = Ia ka C + sum over lights  k Ip (kd max(L.N, 0) C + ks max(R.V, 0)^n),
//   R = 2 (L.N) N - L,
// with no term at all from a light behind the surface (L.N <= 0); k = 1 / (c + l d + q d^2)
// for an attenuated point light, 1 otherwise. Ambient and diffuse multiply the material
// colour; specular multiplies the light's colour. All vectors are unit length, in view space.
//
// Programs are specialised when compiled (the renderer's defines): LIGHT_COUNT (1 to 8)
// lights whose kinds are the list LIGHT_KINDS (each DIRECTIONAL, POINT, ATTENUATED or
// SPOT: a point light times KHR_lights_punctual's cone, clamp(cos a scale + offset)^2),
// ORTHOGRAPHIC, and FLAT_CONSTANTS (where the per-draw constants come from: constants.glsl).
// Each light's term is then straight-line code: no loop over uniform arrays, no branch on
// a uniform that the software rasterizer would evaluate on both sides.

#include "constants.glsl"

// How much of light i reaches the point: 1 unless a fragment stage has a shadow pass's
// visibility (shadow_mask.glsl, included before this file, defines it per pixel).
#ifndef LIGHT_VISIBLE
#define LIGHT_VISIBLE(i) 1.0
#endif

// KHR_lights_punctual's range window, clamp(1 - (d / range)^4, 0, 1)^2; 1 where a light has
// no range (its position's w, the reciprocal of the range, is 0).
float range_window(float dist, float inverse_range) {
    float x = dist * inverse_range;
    float w = clamp(1.0 - x * x * x * x, 0.0, 1.0);
    return w * w;
}

// Unit vector from the point towards the eye: along +z everywhere for an orthographic camera.
vec3 view_dir(vec3 p_view) {
#ifdef ORTHOGRAPHIC
    return vec3(0.0, 0.0, 1.0);
#else
    return normalize(-p_view);
#endif
}

#ifdef PBR
// (glTF's metallic-roughness model in the notes' place: its light_term and ambient term)
#include "pbr.glsl"
#define MODEL_AMBIENT pbr_ambient(n_view, v_view)
#else
#define MODEL_AMBIENT AMBIENT_TERM
// One light's diffuse and specular terms, k kd max(L.N, 0) Ip C (returned) and
// k ks max(R.V, 0)^n Ip (``specular``); `kind` is a constant, so each call compiles to the
// code of its kind alone.
vec3 light_term_parts(int i, int kind, vec3 p_view, vec3 n_view, vec3 v_view,
                      out vec3 specular) {
    vec3 l = LIGHT_POS_VIEW(i).xyz;
    float k = 1.0;
    if (kind != DIRECTIONAL) {
        vec3 to_light = l - p_view;
        float dist = length(to_light);
        l = to_light / max(dist, 1e-30);
        if (kind == ATTENUATED || kind == SPOT) {  // (a light with a range is ATTENUATED)
            vec3 att = LIGHT_ATTENUATION(i);
            k = range_window(dist, LIGHT_POS_VIEW(i).w) /
                max(att.x + att.y * dist + att.z * dist * dist, 1e-30);
        }
        if (kind == SPOT) {
            // KHR_lights_punctual's cone: clamp(cos(angle from the axis) scale + offset)^2
            vec4 spot = LIGHT_SPOT(i);
            float s = clamp(dot(spot.xyz, -l) + spot.w, 0.0, 1.0);
            k *= s * s;
        }
    }
    float ln = dot(l, n_view);
    vec3 r = 2.0 * ln * n_view - l;
    float rv = max(dot(r, v_view), 0.0);
    float spec = rv > 0.0 ? pow(rv, SHININESS) : 0.0;
    vec3 diffuse = ln * LIGHT_DIFFUSE(i);
    specular = spec * LIGHT_SPECULAR(i);
    if (kind == ATTENUATED || kind == SPOT) {
        diffuse *= k;
        specular *= k;
    }
    // (no branch: a light behind the surface, L.N <= 0, contributes nothing at all)
    specular = ln > 0.0 ? specular : vec3(0.0);
    return ln > 0.0 ? diffuse : vec3(0.0);
}

// One light's whole term, k (kd max(L.N, 0) Ip C + ks max(R.V, 0)^n Ip).
vec3 light_term(int i, int kind, vec3 p_view, vec3 n_view, vec3 v_view) {
    vec3 specular;
    vec3 diffuse = light_term_parts(i, kind, p_view, n_view, v_view, specular);
    return diffuse + specular;
}
#endif

vec3 light_intensity(vec3 p_view, vec3 n_view, vec3 v_view) {
    vec3 color = MODEL_AMBIENT;
    // a constant trip count over constant kinds: unrolled, each term its kind's code alone
    const int kinds[LIGHT_COUNT] = int[LIGHT_COUNT](LIGHT_KINDS);
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        color += LIGHT_VISIBLE(i) * light_term(i, kinds[i], p_view, n_view, v_view);
    }
    return color;
}

#ifdef SHADOW_MASK
// The same formula with each light's term kept apart (the ambient term is returned): the
// vertex stages of flat and Gouraud shading hand the terms on, so that a pixel drops the
// terms of the lights its surface point does not see (shadow_mask.glsl: visible_sum).
vec3 light_terms(vec3 p_view, vec3 n_view, vec3 v_view, out vec3 terms[LIGHT_COUNT]) {
    const int kinds[LIGHT_COUNT] = int[LIGHT_COUNT](LIGHT_KINDS);
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        terms[i] = light_term(i, kinds[i], p_view, n_view, v_view);
    }
    return MODEL_AMBIENT;
}
#endif

#ifdef NOTES_TEXTURED
// The formula in its two parts, for textured surfaces (textures.glsl): the ambient and
// diffuse terms (returned; the diffuse map, the notes' C, multiplies them) and the
// specular one (``specular``; the specular map multiplies it).
vec3 light_parts(vec3 p_view, vec3 n_view, vec3 v_view, out vec3 specular) {
    vec3 color = AMBIENT_TERM;
    specular = vec3(0.0);
    const int kinds[LIGHT_COUNT] = int[LIGHT_COUNT](LIGHT_KINDS);
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        vec3 s;
        color += LIGHT_VISIBLE(i) * light_term_parts(i, kinds[i], p_view, n_view, v_view, s);
        specular += LIGHT_VISIBLE(i) * s;
    }
    return color;
}

#ifdef SHADOW_MASK
// The same, each light's two terms kept apart (flat and Gouraud with a shadow pass).
vec3 light_terms_parts(vec3 p_view, vec3 n_view, vec3 v_view, out vec3 terms[LIGHT_COUNT],
                       out vec3 specular_terms[LIGHT_COUNT]) {
    const int kinds[LIGHT_COUNT] = int[LIGHT_COUNT](LIGHT_KINDS);
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        terms[i] = light_term_parts(i, kinds[i], p_view, n_view, v_view, specular_terms[i]);
    }
    return AMBIENT_TERM;
}
#endif
#endif
