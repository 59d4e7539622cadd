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
// Scene data (one RGBA32F texture, DATA_WIDTH texels a row, read by texelFetch):
//   HIERARCHY: the BVH in its own RGBA32UI texture (u_bvh; STORAGE_WALK: a storage buffer,
//     walk_nodes, and the walk's triangles from a copy of the table's in another,
//     walk_rows), 2 texels an inner node: its two children packed (geometry/bvh.py,
//     packed_children: a box in 16-bit steps of the root's, rounded outwards, then
//     index << 4 | count); an inner child (count 0) has its own texels at 2 index, a leaf
//     triangles [index, index + count); u_root the root, packed.
//   triangles at u_tris, 3 texels each: (v0, material as int bits), (v1 - v0, model as int
//     bits), (v2 - v0, -);
//     the first FLAT_TRIANGLES also compiled into the program (tested without the BVH)
//   materials at u_mats, 2 texels each: (rho_d, k_s), (E, n)
//   emitters at u_emit, 1 texel each: (cdf, triangle as int bits, area, -)
//   SMOOTH_NORMALS: corner normals at u_norms, 3 texels a triangle (shading normals)
// CSG_SOLID: one CSG solid, ray cast exactly by csg.glsl (the raster pass's code) from its
// own texture; a hit on its leaf L is "triangle" -2 - L, of material u_csg_material.
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
#define STACK 48
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

uniform sampler2D u_data;
uniform usampler2D u_bvh;
#ifdef STORAGE_WALK
// the hierarchy's walk reads its nodes and triangles from storage buffers (GL 4.3: on
// llvmpipe 1.2x the paths a second of texel fetches through the large scene; the other
// reads stay texel fetches, which measured faster where few)
layout(std430, binding = BINDING_WALK_NODES) readonly buffer WalkNodes { uvec4 walk_nodes[]; };
layout(std430, binding = BINDING_WALK_TRIANGLES) readonly buffer WalkRows { vec4 walk_rows[]; };
#endif
#include "packed_box.glsl"
uniform int u_tris;
uniform int u_mats;
uniform int u_emit;
uniform int u_n_emit;
uniform float u_emit_power;   // the emitters' power, sum of area x mean(E) (MIS)
uniform int u_norms;
uniform mat4 u_inverse_proj;     // clip -> view (rays.glsl)
uniform mat4 u_camera_to_world; // view -> world
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
#if LIGHTS > 0  // (the scene's point and directional lights, LIGHTS of them)
uniform vec4 u_light_pos[LIGHTS];  // (position or direction to the light, kind: 0 dir, 1 point)
uniform vec3 u_light_irr[LIGHTS];
uniform vec3 u_light_att[LIGHTS];
#endif
#ifdef PROBES
// rays given per pixel (PROBES: origin at u_rays row 2y, direction at row 2y + 1)
uniform sampler2D u_rays;
#endif

layout(location = 0) out vec4 out_state0;  // origin, bounces made + 1 (0: no path)
layout(location = 1) out vec4 out_state1;  // direction, random state's low 16 bits
layout(location = 2) out vec4 out_state2;  // throughput, random state's high 16 bits
layout(location = 3) out vec4 out_state3;  // the path's value so far, flags (1 emits, 2 hit)
layout(location = 4) out vec4 out_sum;     // finished samples: sum of values, count
layout(location = 5) out vec4 out_square;  // sum of squares, first hits on an emitter
layout(location = 6) out vec4 out_hit;     // camera rays that hit, bounces near the limit,
                                           // the path in flight's last bounce density


#include "random.glsl"
#include "rays.glsl"
#include "data.glsl"
#include "pixel_blocks.glsl"

// The random numbers a path's vertex draws: three for next-event estimation (which
// emitter, then where on it: part 0) and three for the bounce (which lobe, then the
// direction: part 1). LOW_DISCREPANCY: at the first SOBOL_VERTICES vertices they come
// from Owen-scrambled Sobol pairs (random.glsl; a part's point from one pair, its choice
// from the next pair's first coordinate), deeper ones and the roulette from the PCG stream
// -- consumed all the same, so the stream's place never depends on which was used.
uint g_sample;  // this path's sample number in its pixel
int g_vertex;   // the vertex being made (0: the camera ray's hit)
#ifndef SOBOL_VERTICES
#define SOBOL_VERTICES 3
#endif

vec3 sample3(uint part) {
#ifdef LOW_DISCREPANCY
    if (g_vertex < SOBOL_VERTICES) {
        skip(3u);  // (the stream moves on as if it had drawn them)
        uint base = 1u + 2u * (2u * uint(g_vertex) + part);
        return vec3(sobol_pair(g_sample, base + 1u).x, sobol_pair(g_sample, base));
    }
#endif
    return vec3(rand(), rand(), rand());
}

// the camera ray's place in its pixel (Sobol's pair 0 where LOW_DISCREPANCY)
vec2 jitter() {
#ifdef LOW_DISCREPANCY
    skip(2u);
    return sobol_pair(g_sample, 0u);
#else
    return vec2(rand(), rand());
#endif
}

vec4 fetch(int i) {
    return data_texel(u_data, i, DATA_WIDTH);
}

uvec4 bvh_texel(int i) {
#ifdef STORAGE_WALK
    return walk_nodes[i];
#else
    return texelFetch(u_bvh, ivec2(i % DATA_WIDTH, i / DATA_WIDTH), 0);
#endif
}

// row i of the triangle table (u_tris + i of the whole), read by the hierarchy's walk
vec4 walk_fetch(int i) {
#ifdef STORAGE_WALK
    return walk_rows[i];
#else
    return fetch(u_tris + i);
#endif
}

// nearest hit along o + t d, t in (0, t_max): its t, triangle, barycentrics (``any_hit``:
// any hit will do -- a shadow ray's -- so the hierarchy's walk stops at the first)
vec2 g_uv;  // (the nearest hit's barycentrics, set by intersect)

#ifdef FLAT_TRIANGLES
// triangles compiled into the program (all of a small scene's, or a larger one's small
// models beside a HIERARCHY of the rest: the table's first FLAT_TRIANGLES): their rows
// (p0, e1, e2) as constants (FLAT_ROWS: each component's float bits), tested by
// straight-line code (FLAT_TESTS: one FLAT_TEST(k) a triangle), so every read is a
// constant the compiler folds into the test -- on llvmpipe 2.6x the speed of a loop over
// the same rows held as uniforms (measured)
const vec3 FLAT_ROW[3 * FLAT_TRIANGLES] = vec3[](FLAT_ROWS);
#endif

// Moller-Trumbore against triangle k (rows p0, e1 = p1 - p0, e2 = p2 - p0): the nearer hit
// kept
void test_rows(int k, vec3 p0, vec3 e1, vec3 e2, vec3 o, vec3 d, inout float t_hit,
               inout int tri_hit) {
    vec3 pv = cross(d, e2);
    float det = dot(e1, pv);
    if (abs(det) < 1e-30) return;
    float f = 1.0 / det;
    vec3 s = o - p0;
    float u = f * dot(s, pv);
    if (u < 0.0 || u > 1.0) return;
    vec3 q = cross(s, e1);
    float v = f * dot(d, q);
    if (v < 0.0 || u + v > 1.0) return;
    float t = f * dot(e2, q);
    if (t > 0.0 && t < t_hit) {
        t_hit = t;
        tri_hit = k;
        g_uv = vec2(u, v);
    }
}

// triangle k of the table (a hierarchy's leaf)
void test_triangle(int k, vec3 o, vec3 d, inout float t_hit, inout int tri_hit) {
    test_rows(k, walk_fetch(3 * k).xyz, walk_fetch(3 * k + 1).xyz, walk_fetch(3 * k + 2).xyz,
              o, d, t_hit, tri_hit);
}

bool intersect(vec3 o, vec3 d, float t_max, bool any_hit, out float t_hit, out int tri_hit) {
    t_hit = t_max;
    tri_hit = -1;
#ifdef FLAT_TRIANGLES
    // the triangles compiled in: every one in turn, no loop (on a few dozen triangles the
    // nodes' fetches and the walk cost more than the tests they save; measured)
#define FLAT_TEST(k) test_rows(k, FLAT_ROW[3 * k], FLAT_ROW[3 * k + 1], FLAT_ROW[3 * k + 2], \
                               o, d, t_hit, tri_hit);
    FLAT_TESTS
#endif
#ifdef HIERARCHY
    // the hierarchy: a step tests both children of an inner node (the nearer one taken
    // next, the other kept with its entry distance); a ray walks down inner nodes until it
    // holds a leaf, then tests the leaf (one kind of work a SIMD step: llvmpipe runs every
    // branch of a step); kept children farther than the nearest hit so far are dropped
    vec3 inv = 1.0 / d;
    const uint DONE = 0xFFFFFFFFu;
    uint stack[STACK];
    float entry[STACK];
    int top = 0;
    uint item = packed_box_entry(u_root, o, inv, 0.0, t_hit) >= 0.0 &&
                !(any_hit && tri_hit != -1) ? u_root.w : DONE;
    while (item != DONE) {
        while (item != DONE && (item & 15u) == 0u) {
            ++g_iter;
            int row = 2 * int(item >> 4);
            uvec4 left = bvh_texel(row), right = bvh_texel(row + 1);
            float a = packed_box_entry(left, o, inv, 0.0, t_hit);
            float b = packed_box_entry(right, o, inv, 0.0, t_hit);
            bool left_first = b < 0.0 || (a >= 0.0 && a <= b);
            stack[top] = left_first ? right.w : left.w;
            entry[top] = left_first ? b : a;
            top += a >= 0.0 && b >= 0.0 && top < STACK - 1 ? 1 : 0;
            item = a >= 0.0 || b >= 0.0 ? (left_first ? left.w : right.w) : DONE;
            while (item == DONE && top > 0) {
                ++g_iter;  // (the driver counts these too)
                --top;
                item = entry[top] <= t_hit ? stack[top] : DONE;
            }
        }
        if (item == DONE) break;
        int first = int(item >> 4), count = int(item & 15u);
        for (int k = first; k < first + count; ++k) {
            ++g_iter;
            test_triangle(k, o, d, t_hit, tri_hit);
        }
        item = DONE;
        if (any_hit && tri_hit != -1) break;
        while (item == DONE && top > 0) {
            ++g_iter;
            --top;
            item = entry[top] <= t_hit ? stack[top] : DONE;
        }
    }
#endif
#ifdef CSG_SOLID
    float tc;
    int leaf = csg_first_hit(o, d, tc);
    if (leaf >= 0 && tc > 0.0 && tc < t_hit) {
        t_hit = tc;
        tri_hit = -2 - leaf;
    }
#endif
    return tri_hit != -1;
}

bool visible(vec3 o, vec3 d, float dist) {
    float t;
    int k;
    return !intersect(o, d, dist, true, t, k);
}

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

// MIS (Veach's power heuristic): the weight of a sample drawn with density a where another
// strategy would have drawn it with density b
float power_weight(float a, float b) {
    return a * a / max(a * a + b * b, 1e-38);
}

// the emitter triangle r (uniform in [0, 1)) picks by power: its chance p, its area, rows
// (p0, e1, e2) and emission E
void pick_emitter(float r, out float p, out float area, out vec3 q0, out vec3 q1,
                  out vec3 q2, out vec3 e) {
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
    int ek = floatBitsToInt(em.y);
    vec4 p0 = fetch(u_tris + 3 * ek);
    q0 = p0.xyz;
    q1 = fetch(u_tris + 3 * ek + 1).xyz;
    q2 = fetch(u_tris + 3 * ek + 2).xyz;
    e = fetch(u_mats + 2 * floatBitsToInt(p0.w) + 1).xyz;
#endif
}

// next-event estimation (pi x radiance, before the throughput): one emitter triangle by
// power, a point uniform on it, its light through the BRDF where xo sees it. MIS: weighed
// against the bounce's chance of finding the same point (``last``: no bounce follows)
vec3 emitters_seen(vec3 xo, vec3 n, vec3 n_geo, vec3 wo, vec3 rho, float ks, float shin,
                   bool last) {
#ifndef EMITTERS
    return vec3(0.0);  // (none: compiled away -- llvmpipe would run the code all the same)
#endif
    vec3 u = sample3(0u);  // (the emitter, then a point on it)
    float p, area;
    vec3 q0, q1, q2, e;
    pick_emitter(u.x, p, area, q0, q1, q2, e);
    float a = u.y, b = u.z;
    if (a + b > 1.0) { a = 1.0 - a; b = 1.0 - b; }
    vec3 y = q0 + a * q1 + b * q2;
    vec3 ny = normalize(cross(q1, q2));
    vec3 to = y - xo;
    float dist2 = dot(to, to), dist = sqrt(dist2);
    vec3 wi = to / dist;
    float cx = dot(n, wi), cy = -dot(ny, wi);
    if (cx > 0.0 && cy > 0.0 && p > 0.0 && dot(n_geo, wi) > 0.0 &&
        visible(xo, wi, dist * (1.0 - 1e-4))) {
        float w = 1.0;
#ifdef MIS
        float light_pdf = p / area * dist2 / cy;  // (solid angle)
        w = last ? 1.0 : power_weight(light_pdf, bounce_pdf(rho, ks, shin, n, wo, wi));
#endif
        return brdf_pi(rho, ks, shin, n, wi, wo) / PI * e * (cx * cy / dist2) * (area / p) * w;
    }
    return vec3(0.0);
}

// the point and directional lights' contribution where xo sees them
vec3 lights_seen(vec3 xo, vec3 n, vec3 n_geo, vec3 wo, vec3 rho, float ks, float shin) {
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
        }
        float cx = dot(n, wi);
        if (cx > 0.0 && dot(n_geo, wi) > 0.0 && visible(xo, wi, dist)) {
            sum += brdf_pi(rho, ks, shin, n, wi, wo) * u_light_irr[i] * (cx * att);
        }
    }
#endif
    return sum;
}

int g_model;  // the model of the vertex being made (-1: the CSG solid)
#ifdef CONTROL
uniform vec3 u_control[CONTROL];  // each model's control value (radiosity units)
#endif

// One path's state between bounces (see the header).
struct Path {
    vec3 o, d, beta, value;
    int bounces;      // vertices found so far
    float flags;      // 1: its first hit emits; 2: its camera ray hit anything
    float pdf;        // the density d was drawn with by the last bounce (0: a camera ray)
};

bool next_direction(inout Path p, vec3 xo, vec3 n, vec3 n_geo, vec3 wo, vec3 rho, float ks,
                    float shin);

// one bounce of ``p``: the next vertex, its emission (first vertex), next-event estimation
// and the next direction; false when the path ends
bool bounce(inout Path p) {
    g_vertex = p.bounces;
    float t;
    int k;
    if (!intersect(p.o, p.d, 1e30, false, t, k)) return false;
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
        vec3 ns = normalize((1.0 - g_uv.x - g_uv.y) * fetch(u_norms + 3 * k).xyz +
                            g_uv.x * fetch(u_norms + 3 * k + 1).xyz +
                            g_uv.y * fetch(u_norms + 3 * k + 2).xyz);
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

// sample k of this pixel, from its start: its random stream and its camera (or given) ray
Path start(uvec2 pixel, uint k) {
    uvec2 block = pixel / COHERENT_TILE;
    g_state = pcg(pcg(pcg(pcg(u_seed) + block.x) + block.y) + k);
    g_sample = k;
    Path p;
#ifdef PROBES
    p.o = texelFetch(u_rays, ivec2(pixel.x, 2 * int(pixel.y)), 0).xyz;
    p.d = texelFetch(u_rays, ivec2(pixel.x, 2 * int(pixel.y) + 1), 0).xyz;
#else
    vec2 ndc = 2.0 * (vec2(pixel) + jitter()) / u_size - 1.0;
    pixel_ray(u_inverse_proj, u_camera_to_world, ndc, p.o, p.d);
    p.d = normalize(p.d);
#endif
    p.beta = vec3(1.0);
    p.value = vec3(0.0);
    p.bounces = 0;
    p.flags = 0.0;
    p.pdf = 0.0;
    return p;
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
