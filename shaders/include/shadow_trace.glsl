// Exact cast shadows, one ray: whether anything of the scene's triangles lies between a
// surface point and a light, through a BVH (render/passes/shadows.py writes the buffers).
// Shared by the compute pass that fills a pixel's visibility from the G-buffer
// (shadow_rays.comp) and by fragment programs that trace their own point as they shade
// (SHADOW_RAYS_FORWARD, shadow_mask.glsl). A ray's loop iterations are counted and bounded
// (llvmpipe stops a shader at 65,535, silently): one that runs out answers -1, which the
// caller counts in `undecided` and shows as seen (the pass reports the count).
//
//   nodes: an inner node's two children, packed (geometry/bvh.py, packed_children): a
//     child's box (16-bit steps of the root's box, rounded outwards) and index << 4 |
//     count; an inner child (count 0) has its own children at 2 index and 2 index + 1, a
//     leaf triangles [index, index + count)
//   tris: three uvec4 a triangle: v0 and its polygon's id (-1: none), v1 - v0, v2 - v0,
//     read whole (a struct of vec3s is read a float at a time) and as bits (an int carried
//     through a float is a denormal, which a GPU may flush to 0)
// The ray leaves the point eps off the surface (along its polygon's normal, on the light's
// side) at t_min = eps, eps relative to the point's depth and the scene's scale, and skips
// the polygon the point is on (a planar polygon cannot shade itself; its neighbours can).
#ifndef SHADOW_TRACE_GLSL
#define SHADOW_TRACE_GLSL

layout(std430, binding = BINDING_WALK_NODES) readonly buffer Nodes { uvec4 nodes[]; };
#include "packed_box.glsl"
layout(std430, binding = BINDING_WALK_TRIANGLES) readonly buffer Tris { uvec4 tris[]; };
layout(std430, binding = BINDING_RAY_COUNTS) buffer Counts { uint undecided; };
// each mesh polygon's world unit normal, by id (padded to vec4); ids past u_polygons (a
// patch's, a solid's leaf) take the surface's shading normal
layout(std430, binding = BINDING_POLYGON_NORMALS) readonly buffer Normals { vec4 polygon_normals[]; };
uniform int u_polygons;
uniform float u_scale;             // the scene's largest coordinate (float32 precision)
uniform float u_eps;               // relative offset of a ray's start
uniform int u_budget;              // loop iterations a ray may take
uniform int u_has_triangles;       // 0: no hierarchy (no triangles but the big ones)
uniform int u_big;                 // the first u_big triangles: tested by every ray
uniform vec4 u_shadow_lights[8];   // world: point (xyz, 1), direction TO it (xyz, 0);
                                   // w = 2: casts no shadows (always seen)

#define STACK 64

// Whether the ray o + t d, t in (t_min, t_max), meets triangle k (not of polygon own).
bool meets(int k, vec3 o, vec3 d, float t_min, float t_max, int own) {
    uvec4 a = tris[3 * k];
    if (int(a.w) == own) return false;
    vec3 e1 = uintBitsToFloat(tris[3 * k + 1].xyz), e2 = uintBitsToFloat(tris[3 * k + 2].xyz);
    vec3 pv = cross(d, e2);
    float det = dot(e1, pv);
    if (det == 0.0) return false;
    float f = 1.0 / det;
    vec3 s = o - uintBitsToFloat(a.xyz);
    float u = f * dot(s, pv);
    if (u < 0.0 || u > 1.0) return false;
    vec3 q = cross(s, e1);
    float v = f * dot(d, q);
    if (v < 0.0 || u + v > 1.0) return false;
    float t = f * dot(e2, q);
    return t > t_min && t < t_max;
}


// 1 where something lies on o + t d for t in (t_min, t_max), skipping polygon ``own``; 0
// where nothing does; -1 when the ray ran out of its budget.
int occluded(vec3 o, vec3 d, float t_min, float t_max, int own) {
    int iterations = 0;
    for (int k = 0; k < u_big; ++k) {
        ++iterations;
        if (meets(k, o, d, t_min, t_max, own)) return 1;
    }
    if (u_has_triangles == 0) return 0;
    vec3 inv = 1.0 / d;
    if (packed_box_entry(u_root, o, inv, t_min, t_max) < 0.0) return 0;
    // the stack holds children the ray enters (index << 4 | count): a leaf's triangles are
    // tested when it is taken, an inner node's children's boxes before they are pushed (the
    // nearer one taken next); a step loads 32 bytes
    uint stack[STACK];
    int top = 0;
    uint item = u_root.w;
    const uint DONE = 0xFFFFFFFFu;
    while (item != DONE) {
        // down through inner nodes until this ray holds a leaf (or nothing is left): a
        // SIMD step does one kind of work for all its rays
        while (item != DONE && (item & 15u) == 0u) {
            if (++iterations > u_budget) return -1;
            int index = int(item >> 4);
            uvec4 left = nodes[2 * index], right = nodes[2 * index + 1];
            float a = packed_box_entry(left, o, inv, t_min, t_max);
            float b = packed_box_entry(right, o, inv, t_min, t_max);
            if (top > STACK - 2) return -1;  // (deeper than a median-split tree gets)
            // the nearer child entered next (or the only one), the other one kept
            bool left_first = b < 0.0 || (a >= 0.0 && a <= b);
            stack[top] = left_first ? right.w : left.w;
            top += a >= 0.0 && b >= 0.0 ? 1 : 0;
            item = a >= 0.0 || b >= 0.0 ? (left_first ? left.w : right.w)
                                        : (top > 0 ? stack[--top] : DONE);
        }
        if (item == DONE) break;
        int index = int(item >> 4), count = int(item & 15u);
        for (int k = index; k < index + count; ++k) {
            ++iterations;
            if (meets(k, o, d, t_min, t_max, own)) return 1;
        }
        item = top > 0 ? stack[--top] : DONE;
    }
    return 0;
}

// A shadow ray to a light: its start moved eps off the surface on the light's side, its
// unit direction and reach, and whether the light is behind the point's polygon as seen
// (its own plane hides it: no ray needed).
struct ShadowRay {
    vec3 o;
    vec3 d;
    float dist;
    float eps;
    bool behind;
};

// The ray from world point p (view depth ``depth``) to ``light`` (a u_shadow_lights row);
// ``own``: the point's polygon id (-2: none), ``shading_n`` the surface's normal as seen
// (used where the point is on no mesh polygon), ``to_eye`` towards the eye.
ShadowRay shadow_ray(vec3 p, float depth, vec4 light, int own, vec3 shading_n, vec3 to_eye) {
    ShadowRay r;
    vec3 d = light.w > 0.5 ? light.xyz - p : light.xyz;
    r.dist = light.w > 0.5 ? length(d) : 3.4e38;
    r.d = light.w > 0.5 ? d / max(r.dist, 1e-30) : d;
    r.eps = u_eps * (depth + u_scale);
    // start eps off the surface on the light's side of its polygon (a concave crease's
    // neighbour rises over the point: a grazing ray that started on the surface would
    // clip it), then eps along the ray
    bool polygon = own >= 0 && own < u_polygons;
    vec3 n = polygon ? polygon_normals[max(own, 0)].xyz : shading_n;
    r.behind = polygon && dot(n, r.d) * dot(n, to_eye) < 0.0;
    r.o = p + (dot(n, r.d) < 0.0 ? -r.eps : r.eps) * n;
    return r;
}

// Whether ``light`` reaches world point p: 1 seen, 0 hidden by a triangle, -1 undecided
// (the ray ran out of its budget). A light that casts no shadows is always seen.
int light_seen(vec3 p, float depth, vec4 light, int own, vec3 shading_n, vec3 to_eye) {
    if (light.w > 1.5) return 1;
    ShadowRay r = shadow_ray(p, depth, light, own, shading_n, to_eye);
    int hit = r.behind ? 1 : occluded(r.o, r.d, r.eps, r.dist - r.eps, own);
    return hit < 0 ? -1 : 1 - hit;
}
#endif
