// What the path tracer's vertex reflects (trace_integrator.glsl's bounce): material m's
// BRDF (trace_bsdf.glsl's Bsdf) from the materials table, times the colours on geometry
// across triangle k (VERTEX_COLORS) and its maps read there (MAPS, trace_maps.glsl), in
// glTF's model its metallic and roughness (PBR).
#ifndef TRACE_SURFACE_GLSL
#define TRACE_SURFACE_GLSL
#ifdef MAPS
#include "trace_maps.glsl"
#endif

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
