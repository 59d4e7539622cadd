// The path tracer's light (pathtrace.frag): next-event estimation to the emitting
// triangles (one by power, a point uniform on it) and to the point and directional lights,
// each through a shadow ray (trace_scene.glsl's visible); MIS weights (Veach's power
// heuristic) against the bounce's density (trace_bsdf.glsl).
#ifndef TRACE_LIGHTS_GLSL
#define TRACE_LIGHTS_GLSL
// emitters at u_emit (trace_scene.glsl's table), 1 texel each: (cdf, triangle as int bits,
// area, -)
uniform int u_emit;
uniform int u_n_emit;
uniform float u_emit_power;   // the emitters' power, sum of area x mean(E) (MIS)
#if LIGHTS > 0  // (the scene's point and directional lights, LIGHTS of them)
uniform vec4 u_light_pos[LIGHTS];  // (position or direction to the light, kind: 0 dir, 1 point,
                                   // 2 spot)
uniform vec3 u_light_irr[LIGHTS];
uniform vec3 u_light_att[LIGHTS];
uniform vec4 u_light_spot[LIGHTS];  // a spot's axis x its cone's scale, the cone's offset
uniform float u_light_range[LIGHTS];  // 1 / a light's range (0: none)
#endif

// whether a path passes through material m's surface (CUTOUTS: opacity below 1 is a thin
// surface that lets the light through with the chance 1 - opacity, what the rasterizer's
// "over" blends)
bool passes_through(int m, int k, vec2 bary) {
    float opacity = fetch(u_mats + 3 * m + 2).w;
#ifdef MAPS
    if (k >= 0) opacity *= map_slot(m, k, 4, bary, vec4(1.0)).a;  // (its opacity map)
#endif
    return opacity < 1.0 && rand() >= opacity;
}

// whether nothing blocks the segment from o along d for dist: with CUTOUTS each surface
// met, nearest first, lets it through by its chance (at most CUTOUT_LAYERS of them)
#define CUTOUT_LAYERS 16
bool clear_path(vec3 o, vec3 d, float dist) {
#ifdef CUTOUTS
    Hit hit;
    for (int i = 0; i < CUTOUT_LAYERS; ++i) {
        ++g_iter;
        if (!intersect(o, d, dist, false, hit)) return true;
#ifdef CSG_SOLID
        int m = hit.k <= -2 ? u_csg_material : floatBitsToInt(fetch(u_tris + 3 * hit.k).w);
#else
        int m = floatBitsToInt(fetch(u_tris + 3 * hit.k).w);
#endif
        if (!passes_through(m, hit.k, hit.uv)) return false;
        o += d * (hit.t + u_eps);
        dist -= hit.t + u_eps;
        if (dist <= 0.0) return true;
    }
    return false;
#else
    return visible(o, d, dist);
#endif
}

// MIS (Veach's power heuristic): the weight of a sample drawn with density a where another
// strategy would have drawn it with density b
float power_weight(float a, float b) {
    return a * a / max(a * a + b * b, 1e-38);
}

// the emitter triangle r (uniform in [0, 1)) picks by power: its chance p, its area, rows
// (p0, e1, e2), emission E (its material's factor: a map multiplies it where the point
// falls) and index ek
void pick_emitter(float r, out float p, out float area, out vec3 q0, out vec3 q1,
                  out vec3 q2, out vec3 e, out int ek) {
#ifdef EMITTER_PICK
    // a few emitters compiled in: each one's numbers as constants, chosen by comparisons
    // with the cumulative chances (no loop, no fetch; generated, render/passes/pathtrace.py)
    EMITTER_PICK
#else
    int lo = 0, hi = u_n_emit - 1;  // (the first whose cumulative chance reaches r)
    while (lo < hi) {
        ++g_iter;
        int mid = (lo + hi) / 2;
        if (fetch(u_emit + mid).x < r) lo = mid + 1; else hi = mid;
    }
    vec4 em = fetch(u_emit + lo);
    p = em.x - (lo > 0 ? fetch(u_emit + lo - 1).x : 0.0);
    area = em.z;
    ek = floatBitsToInt(em.y);
    vec4 p0 = fetch(u_tris + 3 * ek);
    q0 = p0.xyz;
    q1 = fetch(u_tris + 3 * ek + 1).xyz;
    q2 = fetch(u_tris + 3 * ek + 2).xyz;
    e = fetch(u_mats + 3 * floatBitsToInt(p0.w) + 1).xyz;
#endif
}

// next-event estimation (pi x radiance, before the throughput): one emitter triangle by
// power, a point uniform on it, its light through the BRDF where xo sees it. MIS: weighed
// against the bounce's chance of finding the same point (``last``: no bounce follows)
vec3 emitters_seen(vec3 xo, vec3 n, vec3 n_geo, vec3 wo, Bsdf bs, bool last) {
#ifndef EMITTERS
    return vec3(0.0);  // (none: compiled away -- llvmpipe would run the code all the same)
#endif
    vec3 u = sample3(0u);  // (the emitter, then a point on it)
    float p, area;
    vec3 q0, q1, q2, e;
    int ek;
    pick_emitter(u.x, p, area, q0, q1, q2, e, ek);
    float a = u.y, b = u.z;
    if (a + b > 1.0) { a = 1.0 - a; b = 1.0 - b; }
#ifdef MAPS
    e = surface_emission(floatBitsToInt(fetch(u_tris + 3 * ek).w), ek, e, vec2(a, b), true);
#endif
    vec3 y = q0 + a * q1 + b * q2;
    vec3 ny = normalize(cross(q1, q2));
    vec3 to = y - xo;
    float dist2 = dot(to, to), dist = sqrt(dist2);
    vec3 wi = to / dist;
    float cx = dot(n, wi), cy = -dot(ny, wi);
    if (cx > 0.0 && cy > 0.0 && p > 0.0 && dot(n_geo, wi) > 0.0 &&
        clear_path(xo, wi, dist * (1.0 - 1e-4))) {
        float w = 1.0;
#ifdef MIS
        float light_pdf = p / area * dist2 / cy;  // (solid angle)
        w = last ? 1.0 : power_weight(light_pdf, bounce_pdf(bs, n, wo, wi));
#endif
        return brdf_pi(bs, n, wi, wo) / PI * e * (cx * cy / dist2) * (area / p) * w;
    }
    return vec3(0.0);
}

// the point and directional lights' contribution where xo sees them
vec3 lights_seen(vec3 xo, vec3 n, vec3 n_geo, vec3 wo, Bsdf b) {
    vec3 sum = vec3(0.0);
#if LIGHTS > 0  // (none: no loop, whose body llvmpipe would run once, its ray's tests too)
    for (int i = 0; i < LIGHTS; ++i) {
        ++g_iter;
        vec3 wi = u_light_pos[i].xyz;
        float dist = 1e30, att = 1.0;
        if (u_light_pos[i].w > 0.5) {
            vec3 to = u_light_pos[i].xyz - xo;
            dist = length(to);
            wi = to / dist;
            vec3 c = u_light_att[i];
            att = 1.0 / max(c.x + c.y * dist + c.z * dist * dist, 1e-30);
#ifdef PBR
            // (glTF's model: candela, so the inverse square, as pbr.glsl lights it)
            if (b.pbr > 0.5) att = 1.0 / max(dist * dist, 1e-30);
#endif
            // (KHR_lights_punctual's range window, as lighting.glsl has it)
            float x = dist * u_light_range[i];
            float window = clamp(1.0 - x * x * x * x, 0.0, 1.0);
            att *= window * window;
            if (u_light_pos[i].w > 1.5) {  // (a spot: KHR_lights_punctual's cone)
                float s = clamp(dot(u_light_spot[i].xyz, -wi) + u_light_spot[i].w, 0.0, 1.0);
                att *= s * s;
            }
        }
        float cx = dot(n, wi);
        if (cx > 0.0 && dot(n_geo, wi) > 0.0 && clear_path(xo, wi, dist)) {
            sum += brdf_pi(b, n, wi, wo) * u_light_irr[i] * (cx * att);
        }
    }
#endif
    return sum;
}

// next-event estimation of the sky (pi x radiance, before the throughput): a direction
// drawn by its importance (trace_environment.glsl), its light through the BRDF where xo
// sees out; MIS as for the emitters
vec3 environment_seen(vec3 xo, vec3 n, vec3 n_geo, vec3 wo, Bsdf bs, bool last) {
#ifndef ENVIRONMENT
    return vec3(0.0);
#else
    vec2 u = vec2(rand(), rand());  // (the PCG stream's: Sobol's parts are the others')
    float pdf;
    vec3 wi = env_sample(u, pdf);
    float cx = dot(n, wi);
    if (pdf > 0.0 && cx > 0.0 && dot(n_geo, wi) > 0.0 && clear_path(xo, wi, 1e30)) {
        float w = 1.0;
#ifdef MIS
        w = last ? 1.0 : power_weight(pdf, bounce_pdf(bs, n, wo, wi));
#endif
        return brdf_pi(bs, n, wi, wo) / PI * env_radiance(wi) * (cx / pdf) * w;
    }
    return vec3(0.0);
#endif
}
#endif
