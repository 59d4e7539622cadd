// One ray through a BVH of triangles: the walk and the triangle test that the path tracer
// (pathtrace.frag, trace_scene.glsl) and the exact shadow rays (shadow_trace.glsl) share.
//
// The hierarchy (geometry/bvh.py, packed_children): 2 texels an inner node, its two
// children packed -- a child's box in 16-bit steps of the root's, rounded outwards
// (packed_box.glsl), then index << 4 | count; an inner child (count 0) has its own texels
// at 2 index and 2 index + 1, a leaf the triangles [index, index + count). The includer
// says where the texels are, before the include:
//   uvec4 walk_node(int i)                      node texel i
//   bool walk_rows(int k, out vec3 p0, out vec3 e1, out vec3 e2)
//                                               triangle k's rows (p0, p1 - p0, p2 - p0);
//                                               false: the ray skips it
// A step tests both children of an inner node (the nearer one taken next, the other kept
// with its entry distance); a ray walks down inner nodes until it holds a leaf, then tests
// the leaf (one kind of work a SIMD step: llvmpipe runs every branch of a step); kept
// children farther than the nearest hit so far are dropped. Every loop iteration is
// counted (``iterations``, the driver counts pops too): past ``limit`` the walk stops and
// answers WALK_UNDECIDED (llvmpipe stops a shader at 65,535 loop iterations, silently), as
// it does where the tree is deeper than WALK_STACK (a median split's is not).
#ifndef BVH_WALK_GLSL
#define BVH_WALK_GLSL
#include "packed_box.glsl"

#ifndef WALK_STACK
#define WALK_STACK 64
#endif
// WALK_NEAREST (a program that asks for nearest hits): a kept child's entry distance is
// kept with it, and kept children farther than the nearest hit so far are dropped as they
// are popped (each pop a loop iteration); without it (any-hit rays alone: the shadow
// rays) the next kept child is taken as it is
#ifdef WALK_NEAREST
#define WALK_POP() \
    while (item == DONE && top > 0) { \
        ++iterations; \
        --top; \
        item = entry[top] <= hit.t ? stack[top] : DONE; \
    }
#else
#define WALK_POP() if (item == DONE && top > 0) item = stack[--top]
#endif
#define WALK_MISS 0
#define WALK_HIT 1
#define WALK_UNDECIDED -1

// The nearest hit found so far: its distance (on entry: the farthest a hit may be),
// triangle (-1: none) and barycentrics.
struct Hit {
    float t;
    int k;
    vec2 uv;
};

// Moller-Trumbore: where o + t d meets the triangle (p0, p0 + e1, p0 + e2) for t in
// (t_min, hit.t) -- then ``hit`` becomes triangle k's, and true.
bool hit_triangle(int k, vec3 p0, vec3 e1, vec3 e2, vec3 o, vec3 d, float t_min,
                  inout Hit hit) {
    vec3 pv = cross(d, e2);
    float det = dot(e1, pv);
    if (abs(det) < 1e-30) return false;  // (parallel, or no area: 1 / det would overflow)
    float f = 1.0 / det;
    vec3 s = o - p0;
    float u = f * dot(s, pv);
    if (u < 0.0 || u > 1.0) return false;
    vec3 q = cross(s, e1);
    float v = f * dot(d, q);
    if (v < 0.0 || u + v > 1.0) return false;
    float t = f * dot(e2, q);
    if (t <= t_min || t >= hit.t) return false;
    hit = Hit(t, k, vec2(u, v));
    return true;
}

// Triangle k of the hierarchy's table against the ray.
bool walk_triangle(int k, vec3 o, vec3 d, float t_min, inout Hit hit) {
    vec3 p0, e1, e2;
    return walk_rows(k, p0, e1, e2) && hit_triangle(k, p0, e1, e2, o, d, t_min, hit);
}

// The walk from the root for o + t d, t in (t_min, hit.t): WALK_HIT where it found a
// nearer hit (``any``: it stops at the first), WALK_MISS, or WALK_UNDECIDED.
int walk(vec3 o, vec3 d, float t_min, bool any, int limit, inout int iterations,
         inout Hit hit) {
    vec3 inv = 1.0 / d;
    const uint DONE = 0xFFFFFFFFu;
    uint stack[WALK_STACK];
#ifdef WALK_NEAREST
    float entry[WALK_STACK];
#endif
    int top = 0;
    bool found = false;
    uint item = packed_box_entry(u_root, o, inv, t_min, hit.t) >= 0.0 ? u_root.w : DONE;
    while (item != DONE) {
        while (item != DONE && (item & 15u) == 0u) {
            if (++iterations > limit) return WALK_UNDECIDED;
            int row = 2 * int(item >> 4);
            uvec4 left = walk_node(row), right = walk_node(row + 1);
            float a = packed_box_entry(left, o, inv, t_min, hit.t);
            float b = packed_box_entry(right, o, inv, t_min, hit.t);
            bool left_first = b < 0.0 || (a >= 0.0 && a <= b);
            // (the other child kept where the ray enters both: written always, kept by
            // moving the top -- no branch, which a SIMD step would run both sides of)
            if (top > WALK_STACK - 2) return WALK_UNDECIDED;
            stack[top] = left_first ? right.w : left.w;
#ifdef WALK_NEAREST
            entry[top] = left_first ? b : a;
#endif
            top += a >= 0.0 && b >= 0.0 ? 1 : 0;
            item = a >= 0.0 || b >= 0.0 ? (left_first ? left.w : right.w) : DONE;
            WALK_POP();
        }
        if (item == DONE) break;
        int first = int(item >> 4), count = int(item & 15u);
        for (int k = first; k < first + count; ++k) {
            ++iterations;
            if (walk_triangle(k, o, d, t_min, hit)) {
                if (any) return WALK_HIT;  // (a shadow ray's question is answered)
                found = true;
            }
        }
        item = DONE;
        WALK_POP();
    }
    return found ? WALK_HIT : WALK_MISS;
}

// The nearest triangle on o + t d, t in (t_min, hit.t).
int closest_hit(vec3 o, vec3 d, float t_min, int limit, inout int iterations, inout Hit hit) {
    return walk(o, d, t_min, false, limit, iterations, hit);
}

// Any triangle on o + t d, t in (t_min, hit.t) (a shadow ray's question: the walk stops
// at the first).
int any_hit(vec3 o, vec3 d, float t_min, int limit, inout int iterations, inout Hit hit) {
    return walk(o, d, t_min, true, limit, iterations, hit);
}
#endif
