// What the path tracer's vertex reflects (trace_integrator.glsl's bounce): material m's
// BRDF (trace_bsdf.glsl's Bsdf) from the materials table, times the colours on geometry
// across triangle k (VERTEX_COLORS) and its maps read there (MAPS, trace_maps.glsl), in
// glTF's model its metallic and roughness (PBR).
#ifndef TRACE_SURFACE_GLSL
#define TRACE_SURFACE_GLSL
#ifdef MAPS
#include "trace_maps.glsl"
#endif

// the normal that shades triangle k's point ``bary`` (material m), ``n`` the true one on
// the ray's side: the corners' normals interpolated (SMOOTH_NORMALS), bent by a normal
// map (MAPS: tangent space, the tangent along increasing u, the bitangent w N x T); a CSG
// solid's (not ``on_mesh``) is its own
vec3 shading_normal(int m, int k, vec2 bary, vec3 n, bool on_mesh) {
    if (!on_mesh) return n;
#ifdef SMOOTH_NORMALS
    vec3 ns = normalize((1.0 - bary.x - bary.y) * fetch(u_norms + 3 * k).xyz +
                        bary.x * fetch(u_norms + 3 * k + 1).xyz +
                        bary.y * fetch(u_norms + 3 * k + 2).xyz);
    n = dot(ns, n) < 0.0 ? -ns : ns;  // (on the ray's side)
#endif
#ifdef MAPS
    vec4 bend = map_slot(m, k, 3, bary, vec4(0.5, 0.5, 1.0, 1.0)) * 2.0 - 1.0;
    if (bend.xy != vec2(0.0)) {
        vec4 t = fetch(u_tangents + k);
        vec3 tangent = normalize(t.xyz - n * dot(n, t.xyz));
        n = normalize(tangent * bend.x + t.w * cross(n, tangent) * bend.y + n * bend.z);
    }
#endif
    return n;
}

// ``ma``: the table's first texel of m (rho_d or the base colour, k_s), ``shin`` its n;
// ``bary`` the hit's barycentrics on triangle k, a mesh's (``on_mesh``: not a CSG solid)
Bsdf surface_bsdf(int m, int k, vec4 ma, float shin, vec2 bary, bool on_mesh) {
    Bsdf b = Bsdf(ma.xyz, ma.w, shin, 0.0, 0.0, 0.0);
#ifdef VERTEX_COLORS
    if (on_mesh) {  // (colours on geometry: the surface colour C across the triangle)
        b.rho *= (1.0 - bary.x - bary.y) * fetch(u_cols + 3 * k).xyz +
                 bary.x * fetch(u_cols + 3 * k + 1).xyz + bary.y * fetch(u_cols + 3 * k + 2).xyz;
    }
#endif
#ifdef PBR
    vec4 mc = fetch(u_mats + 3 * m + 2);  // (glTF's model: metallic, roughness, flag)
    b.metallic = mc.x; b.roughness = mc.y; b.pbr = mc.z;
#endif
#ifdef MAPS
    if (on_mesh) apply_maps(b, m, k, bary);
#endif
    return b;
}

// material m's emission ``e`` (its factor) at the point ``bary`` of triangle k: times its
// emissive map there (MAPS), where it has one
vec3 surface_emission(int m, int k, vec3 e, vec2 bary, bool on_mesh) {
#ifdef MAPS
    if (on_mesh && dot(e, vec3(1.0)) > 0.0) e *= map_slot(m, k, 2, bary, vec4(1.0)).rgb;
#endif
    return e;
}
#endif
