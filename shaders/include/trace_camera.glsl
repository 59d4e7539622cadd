// The path tracer's paths (pathtrace.frag): one path's state between bounces, and where
// sample k of a pixel starts -- its random stream and its camera (or given) ray.
#ifndef TRACE_CAMERA_GLSL
#define TRACE_CAMERA_GLSL
#include "rays.glsl"
#include "trace_sampler.glsl"

uniform mat4 u_inverse_proj;     // clip -> view (rays.glsl)
uniform mat4 u_camera_to_world; // view -> world
#ifdef PROBES
// rays given per pixel (PROBES: origin at u_rays row 2y, direction at row 2y + 1)
uniform sampler2D u_rays;
#endif

// One path's state between bounces (see the header).
struct Path {
    vec3 o, d, beta, value;
    int bounces;      // vertices found so far
    float flags;      // 1: its first hit emits; 2: its camera ray hit anything
    float pdf;        // the density d was drawn with by the last bounce (0: a camera ray)
};

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
#endif
