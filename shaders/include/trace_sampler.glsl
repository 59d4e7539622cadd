// The path tracer's samples (pathtrace.frag): which random numbers a path's vertex draws.
#ifndef TRACE_SAMPLER_GLSL
#define TRACE_SAMPLER_GLSL
#include "random.glsl"

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
#endif
