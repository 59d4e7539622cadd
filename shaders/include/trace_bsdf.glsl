// The path tracer's BRDF (pathtrace.frag): rho_d / pi + k_s (n + 2) / (2 pi) cos^n(alpha),
// two-sided, values in radiosity units (pi x the BRDF); the bounce's lobes and density.
#ifndef TRACE_BSDF_GLSL
#define TRACE_BSDF_GLSL

// a unit vector around n with density cos^e / normalisation (e = 1: cosine-weighted)
vec3 around(vec3 n, float cos_t, float phi) {
    vec3 a = abs(n.x) > 0.5 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    vec3 u = normalize(cross(a, n)), v = cross(n, u);
    float sin_t = sqrt(max(0.0, 1.0 - cos_t * cos_t));
    return normalize(u * (cos(phi) * sin_t) + v * (sin(phi) * sin_t) + n * cos_t);
}

// pi x BRDF for light arriving from wi, leaving along wo, at normal n
vec3 brdf_pi(vec3 rho, float ks, float shin, vec3 n, vec3 wi, vec3 wo) {
#ifndef GLOSSY
    return rho;  // (no material has a Phong lobe: its pow compiled away)
#endif
    vec3 r = reflect(-wo, n);
    float ca = max(dot(r, wi), 0.0);
    return rho + vec3(ks * 0.5 * (shin + 2.0) * pow(ca, shin));
}

// the density (solid angle) with which a bounce at normal n, leaving along wo, samples wi
// (the lobe chosen by albedo, as bounce does)
float bounce_pdf(vec3 rho, float ks, float shin, vec3 n, vec3 wo, vec3 wi) {
    float wd = (rho.x + rho.y + rho.z) / 3.0;
    if (wd + ks <= 0.0) return 0.0;
#ifndef GLOSSY
    return max(dot(wi, n), 0.0) / PI;
#endif
    float pd = wd / (wd + ks);
    float ca = max(dot(wi, reflect(-wo, n)), 0.0);
    return pd * max(dot(wi, n), 0.0) / PI + (1.0 - pd) * (shin + 1.0) / (2.0 * PI) *
           pow(ca, shin);
}
#endif
