// The path tracer's BRDFs (pathtrace.frag), values in radiosity units (pi x the BRDF), two-
// sided; each bounce's lobes and density:
//   the notes' model: rho_d / pi + k_s (n + 2) / (2 pi) cos^n(alpha) (the Phong lobe
//     normalised so that it reflects k_s of the light arriving along the normal);
//   glTF's metallic-roughness model (PBR defined): Appendix B's BRDF, the one copy in
//     pbr_brdf.glsl the rasterizer evaluates too; sampled by its lobes, the lobe chosen by
//     its Fresnel weight: GGX's visible normals (Heitz 2018, "Sampling the GGX
//     Distribution of Visible Normals") for the specular one, the cosine for the diffuse.
#ifndef TRACE_BSDF_GLSL
#define TRACE_BSDF_GLSL
#ifdef PBR
#include "pbr_brdf.glsl"
// the least GGX alpha a bounce samples (roughness 0's perfect mirror has no density)
#define MIN_ALPHA 1e-3
#endif

// a surface's reflection, from the materials table (trace_scene.glsl): the notes' rho_d,
// k_s and n; a glTF material's base colour (in rho), metallic and roughness (pbr: > 0.5)
struct Bsdf {
    vec3 rho;
    float ks;
    float shin;
    float metallic;
    float roughness;
    float pbr;
};

// a unit vector around n with density cos^e / normalisation (e = 1: cosine-weighted)
vec3 around(vec3 n, float cos_t, float phi) {
    vec3 a = abs(n.x) > 0.5 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 u = normalize(cross(a, n)), v = cross(n, u);
    float sin_t = sqrt(max(0.0, 1.0 - cos_t * cos_t));
    return normalize(u * (cos(phi) * sin_t) + v * (sin(phi) * sin_t) + n * cos_t);
}

#ifdef PBR
float pbr_alpha(Bsdf b) {
    return max(b.roughness * b.roughness, MIN_ALPHA);
}

// the chance a bounce takes the specular lobe: its Fresnel weight at the view against the
// diffuse lobe's (1 - F)(1 - metallic) mean(base)
float pbr_specular_chance(Bsdf b, vec3 n, vec3 wo) {
    vec3 f0 = mix(vec3(0.04), b.rho, b.metallic);
    float w = 1.0 - clamp(dot(n, wo), 0.0, 1.0);
    float f = dot(f0 + (1.0 - f0) * (w * w * w * w * w), vec3(1.0 / 3.0));
    float d = (1.0 - f) * (1.0 - b.metallic) * dot(b.rho, vec3(1.0 / 3.0));
    return f + d > 0.0 ? f / (f + d) : 1.0;
}

// Smith's G1 of GGX for the view at cosine c
float ggx_g1(float c, float a) {
    return 2.0 * c / (c + sqrt(a * a + (1.0 - a * a) * c * c));
}

// GGX's normal distribution D at cosine c
float ggx_d(float c, float a) {
    float d = c * c * (a * a - 1.0) + 1.0;
    return a * a / (PBR_PI * max(d * d, 1e-30));
}

// a visible normal for the view wo (Heitz 2018, in n's frame), u in [0, 1)^2
vec3 ggx_visible_normal(vec3 n, vec3 wo, float a, vec2 u) {
    vec3 t0 = abs(n.x) > 0.5 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 tx = normalize(cross(t0, n)), ty = cross(n, tx);
    vec3 v = vec3(dot(wo, tx), dot(wo, ty), dot(wo, n));
    vec3 vh = normalize(vec3(a * v.x, a * v.y, v.z));  // (the hemisphere's configuration)
    float len2 = vh.x * vh.x + vh.y * vh.y;
    vec3 t1 = len2 > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(len2) : vec3(1.0, 0.0, 0.0);
    vec3 t2 = cross(vh, t1);
    float r = sqrt(u.x), phi = 2.0 * PBR_PI * u.y;
    float p1 = r * cos(phi), p2 = r * sin(phi);
    float s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * p2;
    vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    vec3 m = normalize(vec3(a * nh.x, a * nh.y, max(0.0, nh.z)));  // (back: stretched)
    return m.x * tx + m.y * ty + m.z * n;
}
#endif

// pi x BRDF for light arriving from wi, leaving along wo, at normal n
vec3 brdf_pi(Bsdf b, vec3 n, vec3 wi, vec3 wo) {
#ifdef PBR
    if (b.pbr > 0.5) {
        float c = dot(n, wi);
        return c > 0.0 ? PBR_PI * pbr_brdf_cos(n, wi, wo, b.rho, b.metallic,
                                               max(b.roughness, sqrt(MIN_ALPHA))) / c
                       : vec3(0.0);
    }
#endif
#ifndef GLOSSY
    return b.rho;  // (no material has a Phong lobe: its pow compiled away)
#endif
    vec3 r = reflect(-wo, n);
    float ca = max(dot(r, wi), 0.0);
    return b.rho + vec3(b.ks * 0.5 * (b.shin + 2.0) * pow(ca, b.shin));
}

// the density (solid angle) with which a bounce at normal n, leaving along wo, samples wi
// (the lobe chosen as sample_bounce chooses it)
float bounce_pdf(Bsdf b, vec3 n, vec3 wo, vec3 wi) {
#ifdef LOBE_UNIFORM
    return dot(wi, n) > 0.0 ? 0.5 / PI : 0.0;  // (uniform over the hemisphere: 1 / 2 pi)
#else
#ifdef PBR
    if (b.pbr > 0.5) {
        float ps = pbr_specular_chance(b, n, wo);
        float a = pbr_alpha(b);
        vec3 h = normalize(wi + wo);
        float nv = max(dot(n, wo), 1e-4), nh = dot(n, h);
#ifdef GGX_NORMALS
        // (a normal h drawn by D(h) N.H gives wi with density D(h) N.H / (4 V.H))
        float spec = nh > 0.0 ? ggx_d(nh, a) * nh / (4.0 * max(dot(wo, h), 1e-4)) : 0.0;
#else
        // (a visible normal h gives wi with density G1(wo) D(h) / (4 N.V))
        float spec = nh > 0.0 ? ggx_g1(nv, a) * ggx_d(nh, a) / (4.0 * nv) : 0.0;
#endif
        return ps * spec + (1.0 - ps) * max(dot(wi, n), 0.0) / PI;
    }
#endif
    float wd = (b.rho.x + b.rho.y + b.rho.z) / 3.0;
    if (wd + b.ks <= 0.0) return 0.0;
#ifndef GLOSSY
    return max(dot(wi, n), 0.0) / PI;
#endif
    float pd = wd / (wd + b.ks);
    float ca = max(dot(wi, reflect(-wo, n)), 0.0);
    return pd * max(dot(wi, n), 0.0) / PI + (1.0 - pd) * (b.shin + 1.0) / (2.0 * PI) *
           pow(ca, b.shin);
#endif
}

// a bounce's direction from u in [0, 1)^3 (the lobe, then a direction in it); zero where
// the surface reflects nothing
vec3 sample_bounce(Bsdf b, vec3 n, vec3 wo, vec3 u) {
#ifdef LOBE_UNIFORM
    return around(n, u.y, 2.0 * PI * u.z);  // (cos theta uniform: uniform in solid angle)
#else
#ifdef PBR
    if (b.pbr > 0.5) {
        if (u.x < pbr_specular_chance(b, n, wo)) {
#ifdef GGX_NORMALS
            float a = pbr_alpha(b);  // (D(h) N.H's inverse: cos^2 = (1 - u) / (1 + (a^2 - 1) u))
            float c2 = (1.0 - u.y) / (1.0 + (a * a - 1.0) * u.y);
            vec3 h = around(n, sqrt(c2), 2.0 * PI * u.z);
#else
            vec3 h = ggx_visible_normal(n, wo, pbr_alpha(b), u.yz);
#endif
            return reflect(-wo, h);
        }
        return around(n, sqrt(u.y), 2.0 * PI * u.z);
    }
#endif
    float wd = (b.rho.x + b.rho.y + b.rho.z) / 3.0;
    if (wd + b.ks <= 0.0) return vec3(0.0);
#ifdef GLOSSY
    float pd = wd / (wd + b.ks);
    bool diffuse = u.x < pd;
    return around(diffuse ? n : reflect(-wo, n),
                  diffuse ? sqrt(u.y) : pow(u.y, 1.0 / (b.shin + 1.0)), 2.0 * PI * u.z);
#else
    return around(n, sqrt(u.y), 2.0 * PI * u.z);  // (every lobe diffuse)
#endif
#endif
}
#endif
