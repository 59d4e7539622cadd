#version 430 core
// Exact cast shadows: for each pixel's nearest surface point (from a G-buffer the renderer
// drew: view depth and polygon id) and each light (the z of the invocation), one ray to the
// light through a BVH of the scene's world triangles; any hit before the light hides it.
// One invocation is one ray, its loop iterations counted and bounded (llvmpipe stops a
// shader at 65,535, silently): a ray that runs out is counted in u_counts and its light
// shown as seen (the pass reports the count; it is never hidden).
//
// Buffers (render/passes/shadows.py writes them):
//   nodes: an inner node's two children, packed (geometry/bvh.py, packed_children): a
//     child's box (16-bit steps, rounded outwards) and index << 4 | count; an inner child
//     (count 0) has its own children at 2 index and 2 index + 1, a leaf triangles
//     [index, index + count)
//   tris: three uvec4 a triangle: v0 and its polygon's id (-1: none), v1 - v0, v2 - v0,
//     read whole (a struct of vec3s is read a float at a time) and as bits (an int carried
//     through a float is a denormal, which a GPU may flush to 0)
// The ray leaves the point eps off the surface (along its polygon's normal, on the light's
// side) at
// t_min = eps, eps relative to the point's depth and the scene's scale (the point is
// rebuilt from a float depth), and skips the polygon the point is on (a planar polygon
// cannot shade itself; its neighbours can).
// CSG_SOLID: this run casts against one CSG solid instead (csg.glsl, the raster pass's
// cast, from the ray's start moved eps towards the light), and only hides more: a light a
// run before found hidden stays hidden (one run a solid, after the triangles').
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

// nodes: an inner node's two children, a uvec4 each (geometry/bvh.py, packed_children):
// the box's corners in 16-bit steps of the root's box, then index << 4 | count
layout(std430, binding = 0) readonly buffer Nodes { uvec4 nodes[]; };
uniform uvec4 u_root;              // the root, packed as a child
uniform vec3 u_qbase;              // a corner q (in steps) lies at u_qbase + q u_qstep
uniform vec3 u_qstep;
layout(std430, binding = 1) readonly buffer Tris { uvec4 tris[]; };
layout(std430, binding = 2) buffer Counts { uint undecided; };
// each mesh polygon's world unit normal, by id (padded to vec4); ids past u_polygons (a
// patch's, a solid's leaf) take the G-buffer's normal
layout(std430, binding = 4) readonly buffer Normals { vec4 polygon_normals[]; };
uniform int u_polygons;
#ifdef CSG_SOLID
layout(r8, binding = 0) uniform image2DArray u_visibility;
int g_iter;
#define CSG_COUNT ++g_iter
#include "csg.glsl"
#else
layout(r8, binding = 0) writeonly uniform image2DArray u_visibility;
#endif

uniform isampler2D u_face_ids;     // polygon id + 1 (0: background), the G-buffer's
uniform usampler2D u_depth_bits;   // floatBitsToUint(view depth)
uniform sampler2D u_normals;       // world normal as (n + 1) / 2 (the shading one, seen side)
// a pixel's ray: its origin and span at the viewport's first pixel and a pixel's steps
uniform vec3 u_origin0, u_origin_dx, u_origin_dy;
uniform vec3 u_span0, u_span_dx, u_span_dy;
uniform vec4 u_viewport;           // x, y, w, h of the draw in the G-buffer's pixels
uniform vec3 u_eye;
uniform vec3 u_forward;            // the view axis (world, unit)
uniform float u_near;
uniform float u_scale;             // the scene's largest coordinate (float32 precision)
uniform float u_eps;               // relative offset of a ray's start
uniform int u_budget;              // loop iterations a ray may take
uniform int u_light_count;
uniform vec4 u_lights[8];          // world: point (xyz, 1), direction TO it (xyz, 0);
                                   // w = 2: casts no shadows (always seen)
uniform int u_has_triangles;      // 0: no hierarchy (no triangles but the big ones)
uniform int u_big;                 // the first u_big triangles: tested by every ray


#define STACK 64

// Whether anything lies on o + t d for t in (t_min, t_max), skipping polygon ``own``; -1
// when the ray ran out of its budget.
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

// The ray's entry into a packed child's box, or a negative number where it misses the box
// within (t_min, t_max).
float enters(uvec4 c, vec3 o, vec3 inv, float t_min, float t_max) {
    vec3 lo = u_qbase + vec3(uvec3(c.x & 0xFFFFu, c.x >> 16, c.y & 0xFFFFu)) * u_qstep;
    vec3 hi = u_qbase + vec3(uvec3(c.y >> 16, c.z & 0xFFFFu, c.z >> 16)) * u_qstep;
    vec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
    vec3 tn = min(t0, t1), tf = max(t0, t1);
    float near = max(max(tn.x, tn.y), max(tn.z, t_min));
    float far = min(min(tf.x, tf.y), min(tf.z, t_max));
    return near <= far ? near : -1.0;
}

int occluded(vec3 o, vec3 d, float t_min, float t_max, int own) {
    int iterations = 0;
    for (int k = 0; k < u_big; ++k) {
        ++iterations;
        if (meets(k, o, d, t_min, t_max, own)) return 1;
    }
    if (u_has_triangles == 0) return 0;
    vec3 inv = 1.0 / d;
    if (enters(u_root, o, inv, t_min, t_max) < 0.0) return 0;
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
            float a = enters(left, o, inv, t_min, t_max);
            float b = enters(right, o, inv, t_min, t_max);
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

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    ivec2 px = id.xy + ivec2(u_viewport.xy);
    int light = id.z;
    if (any(greaterThanEqual(id.xy, ivec2(u_viewport.zw))) || light >= u_light_count) return;
    int face = texelFetch(u_face_ids, px, 0).r;
#ifdef CSG_SOLID
    if (face == 0 || imageLoad(u_visibility, ivec3(px, light)).r == 0.0) return;
#endif
    // (one store at the end: llvmpipe runs every branch, an early store and return too)
    bool trace = face != 0;
    float depth = uintBitsToFloat(texelFetch(u_depth_bits, px, 0).r);
    // the pixel's ray, affine in the pixel (geometry/transforms.py, pixel_rays)
    vec2 at = vec2(id.xy);
#ifdef ORTHOGRAPHIC
    vec3 origin = u_origin0 + at.x * u_origin_dx + at.y * u_origin_dy;
    vec3 p = origin + u_forward * (depth - u_near);
#else
    vec3 span = u_span0 + at.x * u_span_dx + at.y * u_span_dy;
    vec3 p = u_eye + span * (depth / dot(span, u_forward));
#endif
    vec4 l = u_lights[light];
    float seen = 1.0;
    if (trace && l.w < 1.5) {
        vec3 d = l.w > 0.5 ? l.xyz - p : l.xyz;
        float dist = l.w > 0.5 ? length(d) : 3.4e38;
        d = l.w > 0.5 ? d / max(dist, 1e-30) : d;
        float eps = u_eps * (depth + u_scale);
        // start eps off the surface on the light's side of its polygon (a concave crease's
        // neighbour rises over the point: a grazing ray that started on the surface would
        // clip it), then eps along the ray
        bool polygon = face - 1 < u_polygons;
        vec3 n = polygon ? polygon_normals[face - 1].xyz : (texelFetch(u_normals, px, 0).xyz * 2.0 - 1.0);
#ifndef CSG_SOLID
#ifdef ORTHOGRAPHIC
        vec3 to_eye = -u_forward;
#else
        vec3 to_eye = u_eye - p;
#endif
        // the light behind the polygon as seen: its own plane hides it (no ray)
        bool behind = polygon && dot(n, d) * dot(n, to_eye) < 0.0;
#endif
        p += (dot(n, d) < 0.0 ? -eps : eps) * n;
#ifdef CSG_SOLID
        float t;
        g_iter = 0;
        int leaf = csg_first_hit(p + eps * d, d, t);
        int hit = leaf >= 0 && t > 0.0 && t < dist - 2.0 * eps ? 1 : 0;
        if (g_iter > u_budget) hit = -1;  // (counted as the walk went: flagged, not hidden)
        if (hit == 0) return;  // (the triangles' answer stands)
#else
        int hit = behind ? 1 : occluded(p, d, eps, dist - eps, face - 1);
#endif
        if (hit < 0) {
            atomicAdd(undecided, 1u);
        }
        seen = hit == 1 ? 0.0 : 1.0;
    }
    imageStore(u_visibility, ivec3(px, light), vec4(seen));
}
