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
// The integrator is trace_integrator.glsl (shared with the compute kernel, pathtrace.comp);
// its parts: trace_scene.glsl (the scene's tables, and the first hit: the BVH walk the
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

#include "trace_integrator.glsl"

layout(location = 0) out vec4 out_state0;  // origin, bounces made + 1 (0: no path)
layout(location = 1) out vec4 out_state1;  // direction, random state's low 16 bits
layout(location = 2) out vec4 out_state2;  // throughput, random state's high 16 bits
layout(location = 3) out vec4 out_state3;  // the path's value so far, flags (1 emits, 2 hit)
layout(location = 4) out vec4 out_sum;     // finished samples: sum of values, count
layout(location = 5) out vec4 out_square;  // sum of squares, first hits on an emitter
layout(location = 6) out vec4 out_hit;     // camera rays that hit, bounces near the limit,
                                           // the path in flight's last bounce density

void main() {
    vec4 o[7];
    trace_pixel(ivec2(gl_FragCoord.xy), o);
    out_state0 = o[0];
    out_state1 = o[1];
    out_state2 = o[2];
    out_state3 = o[3];
    out_sum = o[4];
    out_square = o[5];
    out_hit = o[6];
}
