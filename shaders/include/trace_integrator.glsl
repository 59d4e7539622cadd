// The path tracer's integrator (pathtrace.frag's header tells the method): a path's bounces
// and one pass's work at one pixel of the targets (``trace_pixel``), for the fragment
// program (pathtrace.frag) and the compute kernel (pathtrace.comp) alike.
#ifndef TRACE_INTEGRATOR_GLSL
#define TRACE_INTEGRATOR_GLSL
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
#include "pixel_blocks.glsl"
// the tables and where a ray meets the scene; the random numbers a vertex draws; the BRDF,
// its lobes and density; next-event estimation and MIS; a path and its camera ray
#include "trace_scene.glsl"
#include "trace_sampler.glsl"
#include "trace_bsdf.glsl"
#ifdef ENVIRONMENT
#include "trace_environment.glsl"
#endif
#include "trace_surface.glsl"
#include "trace_lights.glsl"
#include "trace_camera.glsl"

int g_model;  // the model of the vertex being made (-1: the CSG solid)
#ifdef CONTROL
uniform vec3 u_control[CONTROL];  // each model's control value (radiosity units)
#endif

bool next_direction(inout Path p, vec3 xo, vec3 n, vec3 n_geo, vec3 wo, Bsdf b);

// a path that leaves the scene: the sky it meets, seen by a camera ray; found by a
// bounce, weighed against next-event estimation's chance of drawing the same direction
void leave(inout Path p) {
#ifdef ENVIRONMENT
    vec3 sky = env_radiance(p.d);
    if (p.bounces == 0) {
        p.value += sky;
    } else {
#ifdef MIS
        p.value += p.beta * sky * power_weight(p.pdf, env_pdf(p.d));
#endif
    }
#endif
}

// one bounce of ``p``: the next vertex, its emission (first vertex), next-event estimation
// and the next direction; false when the path ends
bool bounce(inout Path p) {
    g_vertex = p.bounces;
    Hit hit;
    if (!intersect(p.o, p.d, 1e30, false, hit)) {
        leave(p);
        return false;
    }
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
#ifdef CUTOUTS
    if (passes_through(m, k, hit.uv)) {  // (a thin surface: the path goes on as it was, no vertex)
        p.o = x + p.d * u_eps;
        if (p.bounces == 0) p.flags -= 2.0;  // (its first hit is still to come)
        return true;
    }
#endif
    vec4 ma = fetch(u_mats + 3 * m), mb = fetch(u_mats + 3 * m + 1);
    // (next-event estimation chose emitters by their factor's power: MIS weighs by it)
    float e_mean = (mb.x + mb.y + mb.z) / 3.0;
#ifdef MAPS
    mb.xyz = surface_emission(m, k, mb.xyz, hit.uv, k >= 0);
#endif
    if (p.bounces == 0 && dot(ng, p.d) < 0.0) {
        p.value += mb.xyz;  // (emission counted where a camera ray sees it; later via NEE)
        p.flags += float(dot(mb.xyz, vec3(1.0)) > 0.0);
    }
#ifdef MIS
    // later vertices: emission the bounce found, weighed against next-event estimation's
    // chance of choosing this point (none on a solid: its surfaces are not sampled)
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
    n = shading_normal(m, k, hit.uv, n, k >= 0);
    vec3 wo = -p.d;
    Bsdf b = surface_bsdf(m, k, ma, mb.w, hit.uv, k >= 0);
    bool last = u_max_depth > 0 && p.bounces + 1 >= u_max_depth;
    p.value += p.beta * (emitters_seen(xo, n, n_geo, wo, b, last)
                         + lights_seen(xo, n, n_geo, wo, b)
                         + environment_seen(xo, n, n_geo, wo, b, last));
    p.bounces += 1;
    if (u_max_depth > 0 && p.bounces >= u_max_depth) return false;
    return next_direction(p, xo, n, n_geo, wo, b);
}

// the path's next direction from xo: a lobe (by albedo; by Fresnel weight in glTF's model),
// then the BRDF-weighted throughput and Russian roulette; false when the path ends
bool next_direction(inout Path p, vec3 xo, vec3 n, vec3 n_geo, vec3 wo, Bsdf b) {
    vec3 wi = sample_bounce(b, n, wo, sample3(1u));
    float cx = dot(wi, n);
    if (cx <= 0.0 || dot(wi, n_geo) <= 0.0) return false;
    float pdf = bounce_pdf(b, n, wo, wi);
    if (!(pdf > 0.0)) return false;
    p.beta *= brdf_pi(b, n, wi, wo) / PI * cx / pdf;
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
// the count a target pixel past the image holds: more than any run's (always finished)
#define PAST_IMAGE 3.0e38

// One pass at the targets' pixel ``at`` (holding image pixel ``image_of(at)``): its state and
// sums read, the path continued, what the pass leaves there returned in ``o`` -- the seven
// targets in order. The fragment program writes them as its outputs, the compute kernel
// stores them in images: the same code, the same numbers.
void trace_pixel(ivec2 at, out vec4 o[7]) {
    ivec2 image = image_of(at);  // (stream j's copy of the pixel: j image heights up)
    if (image.x >= int(u_size.x) || image.y >= int(u_size.y) * u_streams) {
        // (past the image: no path, and finished, so no pass waits for it)
        o[0] = o[1] = o[2] = o[3] = o[5] = o[6] = vec4(0.0);
        o[4] = vec4(0.0, 0.0, 0.0, PAST_IMAGE);
        return;
    }
    int stream = image.y / int(u_size.y);
    uvec2 pixel = uvec2(image.x, image.y - stream * int(u_size.y));
    // (this stream's share of the samples the pixel should have finished)
    float target = stream_share(min(u_target + texelFetch(u_extra, at, 0).r, u_cap), stream);
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
        // (a stream's samples finish in order: its count gives the sample's number k)
        g_sample = uint(stream) + uint(u_streams) * uint(sum.w);
        if (!flying) {
            if (sum.w >= target) break;
            p = start(pixel, g_sample);
            flying = true;
        }
        bool going = bounce(p);
        if (g_iter >= NEAR_LIMIT) hit.y += 1.0;
        if (!going) {
            sum += vec4(p.value, 1.0);
            square += vec4(p.value * p.value, mod(p.flags, 2.0));
            hit.x += float(p.flags >= 2.0);
            flying = false;
        }
    }
    o[0] = vec4(p.o, flying ? float(p.bounces + 1) : 0.0);
    o[1] = vec4(p.d, float(g_state & 0xFFFFu));
    o[2] = vec4(p.beta, float(g_state >> 16u));
    o[3] = vec4(p.value, p.flags);
    o[4] = sum;
    o[5] = square;
    o[6] = vec4(hit.xy, flying ? p.pdf : 0.0, hit.w);
}
#endif
