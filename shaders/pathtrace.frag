#version 330 core
// A progressive Monte Carlo path tracer for the rendering equation (notes, 23.1). Each pixel
// traces its samples one after another, k = 0, 1, ... (sample k's random stream seeded by
// (seed, pixel, k)), and each pass continues where the last stopped: a path in flight is
// kept in four state targets (origin and bounces, direction, throughput, value so far and
// the random state), so one invocation's work is bounded (new bounces start only under
// u_budget loop iterations: llvmpipe stops a shader at 65,535, silently) and no answer
// depends on how samples are grouped into passes. Finished samples add to three targets:
// their values' sum and count, their squares' sum (for a per-pixel variance) and first hits
// on an emitter, and camera rays that hit anything with the bounces that came near the
// driver's limit (counted, never hidden). Targets are read and written in turn (ping-pong),
// and hold the image in blocks (pixel_blocks.glsl: every llvmpipe thread gets a share of
// the whole image's work).
// Values are in radiosity units (pi x radiance): a diffuse surface shows its radiosity B.
//
// Its parts: trace_scene.glsl (the scene's tables, and the first hit: the BVH walk the
// shadow rays share, bvh_walk.glsl; triangles compiled in; one CSG solid), trace_sampler.glsl
// (a vertex's random numbers), trace_bsdf.glsl (the BRDF), trace_lights.glsl (next-event
// estimation, MIS); this file is the integrator: a path's bounces, a pass's loop.
// BRDF: rho_d / pi + k_s (n + 2) / (2 pi) cos^n(alpha), two-sided; emission one-sided.
// Next-event estimation to the emitters and the lights, then a BRDF-sampled bounce (lobe
// chosen by albedo); emission found by a bounce is not counted again (no double counting) --
// MIS: it is, each way weighed by Veach's power heuristic against the other's density;
// Russian roulette from the fourth vertex (RR_CAP: the most a path may go on with, so a
// lossless room still ends). Random numbers: a PCG stream seeded by nested PCG hashes of
// the seed, the pixel's x and y and the sample k -- or, COHERENT_TILE, of the block of
// pixels it lies in: the block's pixels draw the same numbers, so their rays go the same
// ways and run together in a SIMD step (each pixel's estimate as before; their errors
// correlate).

#define PI 3.14159265358979
#define RR_CAP 0.99
#ifndef DATA_WIDTH
#define DATA_WIDTH 1024
#endif
#ifndef COHERENT_TILE
#define COHERENT_TILE uvec2(1u)  // (the pixels that share random numbers: each its own)
#endif
int g_iter;  // loop iterations so far in this invocation (every loop of the tracer counts,
             // the solid's walk included: CSG_COUNT)
#ifdef CSG_SOLID
#define CSG_COUNT ++g_iter
#include "csg.glsl"
uniform int u_csg_material;
#endif

uniform vec2 u_size;
uniform uint u_seed;
uniform float u_target;       // samples every pixel should have finished when this run ends
uniform sampler2D u_extra;    // and the samples past it this pixel should (adaptive sampling)
uniform float u_cap;          // and at most this many in this step of the run (COHERENT_TILE)
uniform int u_budget;         // loop iterations under which a new bounce may start
uniform int u_max_depth;      // vertices a path may have (<= 0: no limit; roulette ends it)
// the state and sums of the last pass (see the header), read at this pixel
uniform sampler2D u_state0, u_state1, u_state2, u_state3, u_acc0, u_acc1, u_acc2;
uniform float u_eps;
layout(location = 0) out vec4 out_state0;  // origin, bounces made + 1 (0: no path)
layout(location = 1) out vec4 out_state1;  // direction, random state's low 16 bits
layout(location = 2) out vec4 out_state2;  // throughput, random state's high 16 bits
layout(location = 3) out vec4 out_state3;  // the path's value so far, flags (1 emits, 2 hit)
layout(location = 4) out vec4 out_sum;     // finished samples: sum of values, count
layout(location = 5) out vec4 out_square;  // sum of squares, first hits on an emitter
layout(location = 6) out vec4 out_hit;     // camera rays that hit, bounces near the limit,
                                           // the path in flight's last bounce density
#include "pixel_blocks.glsl"
// the tables and where a ray meets the scene; the random numbers a vertex draws; the BRDF,
// its lobes and density; next-event estimation and MIS; a path and its camera ray
#include "trace_scene.glsl"
#include "trace_sampler.glsl"
#include "trace_bsdf.glsl"
#include "trace_lights.glsl"
#include "trace_camera.glsl"

int g_model;  // the model of the vertex being made (-1: the CSG solid)
#ifdef CONTROL
uniform vec3 u_control[CONTROL];  // each model's control value (radiosity units)
#endif

bool next_direction(inout Path p, vec3 xo, vec3 n, vec3 n_geo, vec3 wo, vec3 rho, float ks,
                    float shin);

// one bounce of ``p``: the next vertex, its emission (first vertex), next-event estimation
// and the next direction; false when the path ends
bool bounce(inout Path p) {
    g_vertex = p.bounces;
    Hit hit;
    if (!intersect(p.o, p.d, 1e30, false, hit)) return false;
    float t = hit.t;
    int k = hit.k;
    if (p.bounces == 0) p.flags += 2.0;
    vec3 x = p.o + t * p.d;
    int m;
    vec3 ng;
#ifdef CSG_SOLID
    bool on_solid = k <= -2;
    if (on_solid) {
        m = u_csg_material;
        g_model = -1;
        ng = normalize(csg_normal(-2 - k, x));
    } else
#endif
    {
        vec4 p0 = fetch(u_tris + 3 * k), e1 = fetch(u_tris + 3 * k + 1);
        vec3 e2 = fetch(u_tris + 3 * k + 2).xyz;
        m = floatBitsToInt(p0.w);
        g_model = floatBitsToInt(e1.w);
        ng = normalize(cross(e1.xyz, e2));
    }
    vec4 ma = fetch(u_mats + 2 * m), mb = fetch(u_mats + 2 * m + 1);
    if (p.bounces == 0 && dot(ng, p.d) < 0.0) {
        p.value += mb.xyz;  // (emission counted where a camera ray sees it; later via NEE)
        p.flags += float(dot(mb.xyz, vec3(1.0)) > 0.0);
    }
#ifdef MIS
    // later vertices: emission the bounce found, weighed against next-event estimation's
    // chance of choosing this point (none on a solid: its surfaces are not sampled)
    float e_mean = (mb.x + mb.y + mb.z) / 3.0;
    if (p.bounces > 0 && dot(ng, p.d) < 0.0 && e_mean > 0.0) {
        float light_pdf = e_mean / u_emit_power * t * t / -dot(ng, p.d);
#ifdef CSG_SOLID
        light_pdf = on_solid ? 0.0 : light_pdf;
#endif
        p.value += p.beta * mb.xyz * power_weight(p.pdf, light_pdf);
    }
#endif
    vec3 n = dot(ng, p.d) < 0.0 ? ng : -ng;
    vec3 xo = x + n * u_eps;  // (offsets along the true surface)
    vec3 n_geo = n;
#ifdef SMOOTH_NORMALS
#ifdef CSG_SOLID
    if (!on_solid)
#endif
    {
        vec3 ns = normalize((1.0 - hit.uv.x - hit.uv.y) * fetch(u_norms + 3 * k).xyz +
                            hit.uv.x * fetch(u_norms + 3 * k + 1).xyz +
                            hit.uv.y * fetch(u_norms + 3 * k + 2).xyz);
        n = dot(ns, n) < 0.0 ? -ns : ns;  // (shading normal, on the ray's side)
    }
#endif
    vec3 wo = -p.d;
    vec3 rho = ma.xyz;
    float ks = ma.w, shin = mb.w;
    bool last = u_max_depth > 0 && p.bounces + 1 >= u_max_depth;
    p.value += p.beta * (emitters_seen(xo, n, n_geo, wo, rho, ks, shin, last)
                         + lights_seen(xo, n, n_geo, wo, rho, ks, shin));
    p.bounces += 1;
    if (u_max_depth > 0 && p.bounces >= u_max_depth) return false;
    return next_direction(p, xo, n, n_geo, wo, rho, ks, shin);
}

// the path's next direction from xo: a lobe by albedo, then the BRDF-weighted throughput
// and Russian roulette; false when the path ends
bool next_direction(inout Path p, vec3 xo, vec3 n, vec3 n_geo, vec3 wo, vec3 rho, float ks,
                    float shin) {
    float wd = (rho.x + rho.y + rho.z) / 3.0;
    if (wd + ks <= 0.0) return false;
    float pd = wd / (wd + ks);
    vec3 r = reflect(p.d, n);
    vec3 wi;
    vec3 u = sample3(1u);  // (the lobe, then a direction in it)
#ifdef GLOSSY
    bool diffuse = u.x < pd;
    wi = around(diffuse ? n : r, diffuse ? sqrt(u.y) : pow(u.y, 1.0 / (shin + 1.0)),
                2.0 * PI * u.z);
#else
    wi = around(n, sqrt(u.y), 2.0 * PI * u.z);  // (every lobe diffuse)
#endif
    float cx = dot(wi, n);
    if (cx <= 0.0 || dot(wi, n_geo) <= 0.0) return false;
    float pdf = bounce_pdf(rho, ks, shin, n, wo, wi);
    p.beta *= brdf_pi(rho, ks, shin, n, wi, wo) / PI * cx / pdf;
    if (p.bounces >= 4) {  // (Russian roulette from the fourth vertex on)
        // continue with the throughput's chance (the weight then stays near 1: in a grey
        // room of reflectance rho a path goes on with probability rho), at most RR_CAP
        float q = min(max(p.beta.x, max(p.beta.y, p.beta.z)), RR_CAP);
#ifdef CONTROL
        // the radiosity control variate (radiosity/control.py): c, what the continuation
        // is expected to bring, added whether the path goes on or not; a path that goes on
        // then brings the rest less c, weighted 1 / q -- the same expectation
        vec3 c = g_model >= 0 ? u_control[g_model] : vec3(0.0);
        p.value += p.beta * c;
#endif
        if (rand() >= q) return false;
        p.beta /= q;
#ifdef CONTROL
        p.value -= p.beta * c;
#endif
    }
    p.o = xo;
    p.d = wi;
    p.pdf = pdf;
    return true;
}

// the most bounces one invocation makes (a bound the loop-iteration budget rarely reaches)
#define STEPS 256
// a bounce that ends above this many counted iterations may have met the driver's limit
#define NEAR_LIMIT LOOP_BUDGET

void main() {
    ivec2 at = ivec2(gl_FragCoord.xy);  // (the targets' pixel, holding image pixel ``pixel``)
    ivec2 image = image_of(at);
    float target = min(u_target + texelFetch(u_extra, at, 0).r, u_cap);
    if (image.x >= int(u_size.x) || image.y >= int(u_size.y)) {
        // (past the image: no path, and finished, so no pass waits for it)
        out_state0 = out_state1 = out_state2 = out_state3 = out_square = out_hit = vec4(0.0);
        out_sum = vec4(0.0, 0.0, 0.0, target);
        return;
    }
    uvec2 pixel = uvec2(image);
    vec4 s0 = texelFetch(u_state0, at, 0), s1 = texelFetch(u_state1, at, 0);
    vec4 s2 = texelFetch(u_state2, at, 0), s3 = texelFetch(u_state3, at, 0);
    vec4 sum = texelFetch(u_acc0, at, 0), square = texelFetch(u_acc1, at, 0);
    vec4 hit = texelFetch(u_acc2, at, 0);
    bool flying = s0.w > 0.5;
    Path p;
    p.o = s0.xyz; p.d = s1.xyz; p.beta = s2.xyz; p.value = s3.xyz;
    p.bounces = int(s0.w) - 1;
    p.flags = s3.w;
    p.pdf = hit.z;  // (the path in flight's last bounce density)
    g_state = uint(s1.w) | (uint(s2.w) << 16u);
    g_iter = 0;
#ifdef LOW_DISCREPANCY
    uvec2 block = pixel / COHERENT_TILE;
    g_pixel_seed = pcg(pcg(pcg(u_seed ^ 0x5bd1e995u) + block.x) + block.y);
#endif
    for (int step = 0; step < STEPS && g_iter < u_budget; ++step) {
        if (!flying) {
            if (sum.w >= target) break;
            p = start(pixel, uint(sum.w));  // (samples finish in order: k is the count)
            flying = true;
        }
        g_sample = uint(sum.w);
        bool going = bounce(p);
        if (g_iter >= NEAR_LIMIT) hit.y += 1.0;
        if (!going) {
            sum += vec4(p.value, 1.0);
            square += vec4(p.value * p.value, mod(p.flags, 2.0));
            hit.x += float(p.flags >= 2.0);
            flying = false;
        }
    }
    out_state0 = vec4(p.o, flying ? float(p.bounces + 1) : 0.0);
    out_state1 = vec4(p.d, float(g_state & 0xFFFFu));
    out_state2 = vec4(p.beta, float(g_state >> 16u));
    out_state3 = vec4(p.value, p.flags);
    out_sum = sum;
    out_square = square;
    out_hit = vec4(hit.xy, flying ? p.pdf : 0.0, hit.w);
}
