// The path tracer's scene (pathtrace.frag): its tables in one RGBA32F texture (u_data,
// DATA_WIDTH texels a row, read by texelFetch), and where a ray meets it first.
//   HIERARCHY: the BVH (bvh_walk.glsl) in its own RGBA32UI texture (u_bvh; STORAGE_WALK: a
//     storage buffer, walk_nodes, and the walk's triangles from a copy of the table's in
//     another, walk_table); u_root the root, packed.
//   triangles at u_tris, 3 texels each: (v0, material as int bits), (v1 - v0, model as int
//     bits), (v2 - v0, -);
//     the first FLAT_TRIANGLES also compiled into the program (tested without the BVH)
//   materials at u_mats, 3 texels each: (rho_d or glTF's base colour, k_s), (E, n),
//   (metallic, roughness, 1 for glTF's model else 0, opacity)
//   SMOOTH_NORMALS: corner normals at u_norms, 3 texels a triangle (shading normals)
//   VERTEX_COLORS: corner colours at u_cols, 3 texels a triangle (the surface colour C)
//   ENVIRONMENT: the sky's texels at u_env (trace_environment.glsl)
// CSG_SOLID: one CSG solid, ray cast exactly by csg.glsl (the raster pass's code) from its
// own texture; a hit on its leaf L is "triangle" -2 - L.
#ifndef TRACE_SCENE_GLSL
#define TRACE_SCENE_GLSL
#include "data.glsl"

uniform sampler2D u_data;
uniform usampler2D u_bvh;
#ifdef STORAGE_WALK
// the hierarchy's walk reads its nodes and triangles from storage buffers (GL 4.3: on
// llvmpipe 1.2x the paths a second of texel fetches through the large scene; the other
// reads stay texel fetches, which measured faster where few)
layout(std430, binding = BINDING_WALK_NODES) readonly buffer WalkNodes { uvec4 walk_nodes[]; };
layout(std430, binding = BINDING_WALK_TRIANGLES) readonly buffer WalkRows { vec4 walk_table[]; };
#endif
uniform int u_tris;
uniform int u_mats;
uniform int u_norms;
uniform int u_cols;

vec4 fetch(int i) {
    return data_texel(u_data, i, DATA_WIDTH);
}

// the hierarchy's texels and triangle rows, for the walk (bvh_walk.glsl)
uvec4 walk_node(int i) {
#ifdef STORAGE_WALK
    return walk_nodes[i];
#else
    return texelFetch(u_bvh, ivec2(i % DATA_WIDTH, i / DATA_WIDTH), 0);
#endif
}

bool walk_rows(int k, out vec3 p0, out vec3 e1, out vec3 e2) {
#ifdef STORAGE_WALK
    p0 = walk_table[3 * k].xyz;
    e1 = walk_table[3 * k + 1].xyz;
    e2 = walk_table[3 * k + 2].xyz;
#else
    p0 = fetch(u_tris + 3 * k).xyz;
    e1 = fetch(u_tris + 3 * k + 1).xyz;
    e2 = fetch(u_tris + 3 * k + 2).xyz;
#endif
    return true;
}
#define WALK_STACK 48
#define WALK_NEAREST
#include "bvh_walk.glsl"

#ifdef FLAT_TRIANGLES
// triangles compiled into the program (all of a small scene's, or a larger one's small
// models beside a HIERARCHY of the rest: the table's first FLAT_TRIANGLES): their rows
// (p0, e1, e2) as constants (FLAT_ROWS: each component's float bits), tested by
// straight-line code (FLAT_TESTS: one FLAT_TEST(k) a triangle), so every read is a
// constant the compiler folds into the test -- on llvmpipe 2.6x the speed of a loop over
// the same rows held as uniforms (measured)
const vec3 FLAT_ROW[3 * FLAT_TRIANGLES] = vec3[](FLAT_ROWS);
#endif

// the nearest hit along o + t d, t in (0, t_max) (``any``: any hit will do -- a shadow
// ray's -- so the hierarchy's walk stops at the first): its t, triangle and barycentrics
bool intersect(vec3 o, vec3 d, float t_max, bool any, out Hit hit) {
    hit = Hit(t_max, -1, vec2(0.0));
#ifdef FLAT_TRIANGLES
    // the triangles compiled in: every one in turn, no loop (on a few dozen triangles the
    // nodes' fetches and the walk cost more than the tests they save; measured)
#define FLAT_TEST(k) hit_triangle(k, FLAT_ROW[3 * k], FLAT_ROW[3 * k + 1], \
                                  FLAT_ROW[3 * k + 2], o, d, 0.0, hit);
    FLAT_TESTS
#endif
#ifdef HIERARCHY
    // (no limit of its own: the tracer bounds its work by bounces, u_budget)
    if (!(any && hit.k != -1)) walk(o, d, 0.0, any, 0x7FFFFFFF, g_iter, hit);
#endif
#ifdef CSG_SOLID
    float tc;
    int leaf = csg_first_hit(o, d, tc);
    if (leaf >= 0 && tc > 0.0 && tc < hit.t) {
        hit = Hit(tc, -2 - leaf, vec2(0.0));
    }
#endif
    return hit.k != -1;
}

bool visible(vec3 o, vec3 d, float dist) {
    Hit hit;
    return !intersect(o, d, dist, true, hit);
}
#endif
