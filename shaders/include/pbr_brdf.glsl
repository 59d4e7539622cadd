// glTF 2.0's metallic-roughness BRDF (its specification's Appendix B; the formula is
// pbr.glsl's header), alone: no uniforms, so every program that lights or traces glTF's
// model evaluates this one copy -- the rasterizer's programs through pbr.glsl, the path
// tracer through trace_bsdf.glsl.
#ifndef PBR_BRDF_GLSL
#define PBR_BRDF_GLSL
#define PBR_PI 3.14159265358979

// f(l, v) N.L for unit n, l, v (zero where N.L <= 0).
vec3 pbr_brdf_cos(vec3 n, vec3 l, vec3 v, vec3 base, float metallic, float roughness) {
    float nl = dot(n, l);
    float nv = max(dot(n, v), 1e-4);  // (a silhouette's grazing view, rounded: not 0)
    vec3 h = normalize(l + v);
    float nh = max(dot(n, h), 0.0);
    float vh = max(dot(v, h), 0.0);
    float a = roughness * roughness;
    float a2 = a * a;
    vec3 f0 = mix(vec3(0.04), base, metallic);
    float w = 1.0 - vh;
    vec3 fresnel = f0 + (1.0 - f0) * (w * w * w * w * w);
    float d = nh * nh * (a2 - 1.0) + 1.0;
    float distribution = a2 / (PBR_PI * max(d * d, 1e-30));
    float nlc = max(nl, 0.0);
    float visibility = 0.5 / max(nlc * sqrt(nv * nv * (1.0 - a2) + a2) +
                                 nv * sqrt(nlc * nlc * (1.0 - a2) + a2), 1e-30);
    vec3 diffuse = (1.0 - fresnel) * (1.0 - metallic) * base / PBR_PI;
    vec3 f = diffuse + fresnel * (distribution * visibility);
    return nl > 0.0 ? f * nl : vec3(0.0);
}
#endif
