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

#ifdef SHADOW_TEXELS
// (no storage buffers: a GL 4.1 context's fragment pass, shadow_rays.frag) the same words
// in RGBA32UI / RGBA32F textures, SHADOW_TEXEL_ROW texels a row; the rays that ran out are
// flagged by the caller's output, not counted here
uniform usampler2D u_walk_nodes;
uniform usampler2D u_walk_tris;
uniform sampler2D u_polygon_normals;
ivec2 shadow_texel(int i) {
    return ivec2(i % SHADOW_TEXEL_ROW, i / SHADOW_TEXEL_ROW);
}
#define NODE_WORDS(i) texelFetch(u_walk_nodes, shadow_texel(i), 0)
#define TRI_WORDS(i) texelFetch(u_walk_tris, shadow_texel(i), 0)
#define POLYGON_NORMAL(i) texelFetch(u_polygon_normals, shadow_texel(i), 0)
#else
layout(std430, binding = BINDING_WALK_NODES) readonly buffer Nodes { uvec4 nodes[]; };
layout(std430, binding = BINDING_WALK_TRIANGLES) readonly buffer Tris { uvec4 tris[]; };
layout(std430, binding = BINDING_RAY_COUNTS) buffer Counts { uint undecided; };
// each mesh polygon's world unit normal, by id (padded to vec4); ids past u_polygons (a
// patch's, a solid's leaf) take the surface's shading normal
layout(std430, binding = BINDING_POLYGON_NORMALS) readonly buffer Normals { vec4 polygon_normals[]; };
#define NODE_WORDS(i) nodes[i]
#define TRI_WORDS(i) tris[i]
#define POLYGON_NORMAL(i) polygon_normals[i]
#endif
uniform int u_polygons;
uniform float u_scale;             // the scene's largest coordinate (float32 precision)
uniform float u_eps;               // relative offset of a ray's start
uniform int u_budget;              // loop iterations a ray may take
uniform int u_has_triangles;       // 0: no hierarchy (no triangles but the big ones)
uniform int u_big;                 // the first u_big triangles: tested by every ray
uniform vec4 u_shadow_lights[8];   // world: point (xyz, 1), direction TO it (xyz, 0);
                                   // w = 2: casts no shadows (always seen)

int g_own;  // the polygon the ray leaves from (a planar polygon cannot shade itself)

uvec4 walk_node(int i) {
    return NODE_WORDS(i);
}

bool walk_rows(int k, out vec3 p0, out vec3 e1, out vec3 e2) {
    uvec4 a = TRI_WORDS(3 * k);
    if (int(a.w) == g_own) return false;  // (before the other rows are read)
    p0 = uintBitsToFloat(a.xyz);
    e1 = uintBitsToFloat(TRI_WORDS(3 * k + 1).xyz);
    e2 = uintBitsToFloat(TRI_WORDS(3 * k + 2).xyz);
    return true;
}
#include "bvh_walk.glsl"

// 1 where something lies on o + t d for t in (t_min, t_max), skipping polygon ``own``; 0
// where nothing does; -1 when the ray ran out of its budget.
int occluded(vec3 o, vec3 d, float t_min, float t_max, int own) {
    g_own = own;
    int iterations = 0;
    Hit hit = Hit(t_max, -1, vec2(0.0));
    for (int k = 0; k < u_big; ++k) {
        ++iterations;
        if (walk_triangle(k, o, d, t_min, hit)) return 1;
    }
    if (u_has_triangles == 0) return 0;
    int found = any_hit(o, d, t_min, u_budget, iterations, hit);
    return found == WALK_UNDECIDED ? -1 : found;
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
    vec3 n = polygon ? POLYGON_NORMAL(max(own, 0)).xyz : shading_n;
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
