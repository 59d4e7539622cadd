#version 400 core
// A tensor-product Bezier patch of degree (DEGREE_U, DEGREE_V) over mass-points, evaluated
// at the tessellator's (u, v) by Bernstein sums, with its exact normal Su x Sv (quotient
// rule on the homogeneous derivatives); where that vanishes (a side collapsed to a point:
// the teapot's lid, a sphere's pole) the normal a hair inside the patch, its limit. Then the
// mode's vertex work (stage_smooth.glsl or stage_gouraud.glsl), as for a mesh vertex.
layout(quads, equal_spacing, ccw) in;
#ifdef GOURAUD_STAGE
#include "stage_gouraud.glsl"
#else
#include "stage_smooth.glsl"
#endif

in vec4 e_control[];

// Bernstein polynomials of degree n at t and their derivatives (n <= 7), by products
// (GLSL's pow(0, 0) is undefined, and the patch's sides are at t = 0 and 1)
void bernstein(int n, float t, out float b[8], out float db[8]) {
    float s = 1.0 - t;
    float tp[8], sp[8];
    tp[0] = 1.0;
    sp[0] = 1.0;
    for (int k = 1; k <= n; ++k) {
        tp[k] = tp[k - 1] * t;
        sp[k] = sp[k - 1] * s;
    }
    float c = 1.0;  // binomial(n, i), updated along i
    for (int i = 0; i <= n; ++i) {
        b[i] = c * tp[i] * sp[n - i];
        float d = 0.0;
        if (i > 0) d += float(i) * tp[i - 1] * sp[n - i];
        if (i < n) d -= float(n - i) * tp[i] * sp[n - i - 1];
        db[i] = c * d;
        c = c * float(n - i) / float(i + 1);
    }
}

void surface(vec2 uv, out vec3 p, out vec3 n, out float scale) {
    float bu[8], dbu[8], bv[8], dbv[8];
    bernstein(DEGREE_U, uv.x, bu, dbu);
    bernstein(DEGREE_V, uv.y, bv, dbv);
    vec4 h = vec4(0.0), hu = vec4(0.0), hv = vec4(0.0);
    for (int i = 0; i <= DEGREE_U; ++i) {
        for (int j = 0; j <= DEGREE_V; ++j) {
            vec4 q = e_control[i * (DEGREE_V + 1) + j];
            h += bu[i] * bv[j] * q;
            hu += dbu[i] * bv[j] * q;
            hv += bu[i] * dbv[j] * q;
        }
    }
    p = h.xyz / h.w;
    vec3 su = (hu.xyz - hu.w * p) / h.w, sv = (hv.xyz - hv.w * p) / h.w;
    n = cross(su, sv);
    scale = max(dot(su, su), dot(sv, sv));
}

void main() {
    vec2 uv = gl_TessCoord.xy;
    vec3 p, n;
    float scale;
    surface(uv, p, n, scale);
    if (dot(n, n) <= 1e-10 * scale * scale) {
        vec3 q;
        surface(mix(uv, vec2(0.5), 1e-3), q, n, scale);  // (the limit, from just inside)
    }
    n = normalize(n);
#ifdef GOURAUD_STAGE
    gouraud_stage(p, n);
#else
    smooth_stage(p, n);
#endif
}
