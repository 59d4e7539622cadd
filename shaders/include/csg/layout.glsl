// Where the tree data is and how it is read (solids/encoding.py writes it). A float texture
// holds, for each leaf, its world -> leaf matrix, its normal matrix (negated under a
// difference's right side), sizes and kind; a bounding-volume hierarchy over the leaves'
// world boxes (pre-order, each node with the index past its subtree); the truth table of a
// tree of at most 14 leaves; and the tree as a post-order program for a stack of bits.
//
// A tree of at most 14 leaves (CSG_SLOTS) is cast in one step: see the CSG_SLOTS section.
// A larger one walks. Along the pixel's ray the state of every leaf (inside or not) is
// kept in a bit set. The walk: find the next leaf boundary after the current one (the
// hierarchy skips leaves whose box the ray misses or meets only beyond the best so far);
// flip that leaf's bit; run the
// tree on the bits (a small tree: one lookup in its truth table; else its program, skipping
// subtrees the ray is in none of the leaves of); the first boundary where the tree's answer
// changes is the surface. One pass over the leaves yields the next four boundaries in order.
// Ties (coincident faces, computed through different transforms: equal but for rounding):
// boundaries closer than u_csg_tie are one place (solids/tree.py TIE): the tree's answer is
// taken past all of them, and a surface there is the lowest-numbered leaf's among them.
// Leaf boundaries are exact: closed-form roots, the torus's quartic split at the roots of its
// derivative (a cubic, in closed form) into monotone pieces, each root bracketed and refined
// by bisection on a sign computed without cancellation.
// Built per size class and per set of leaf kinds (CSG_KINDS): on a SIMD rasteriser a branch
// no pixel takes still runs, so only the kinds present are compiled in (see encoding.py); the
// one-step cast per count of leaves of each kind (CSG_KIND_0 ..: each slot's kind).

#ifndef LEAF_SPHERE
#error "the CSG constants (LEAF_*, OP_*, CSG_ROW) come from solids/encoding.py: csg_defines()"
#endif
const float INF = 1e30;
// CSG_COUNT; stands in every loop that grows with the tree: a program that must bound its
// invocations' work (the path tracer) counts them there; elsewhere it is nothing
#ifndef CSG_COUNT
#define CSG_COUNT
#endif
#ifndef CSG_WORDS
#define CSG_WORDS 32                   // words of leaf bits: 32 leaves each (encoding.py picks)
#endif
const int MAX_LEAVES = 32 * CSG_WORDS;
#ifndef CSG_KINDS
#define CSG_KINDS 63                   // the leaf kinds the program serves, a bit each
#endif
// Why: on a SIMD rasteriser (llvmpipe) a branch no pixel takes still runs, masked, so a
// kind's code costs every leaf visit unless the program is built without it.
#define IS(kind, n) ((CSG_KINDS & (1 << (n))) != 0 && (kind) == (n))

#include "data.glsl"

#ifdef CSG_BLOCK
// a small tree: the data in a uniform block (a plain load per read, where a texture read
// costs a sampler's work)
layout(std140) uniform CsgData { vec4 csg_data[CSG_BLOCK]; };
vec4 csg_texel(int i) { return csg_data[i]; }
#else
uniform sampler2D u_csg;               // RGBA32F, CSG_ROW texels a row
vec4 csg_texel(int i) { return data_texel(u_csg, i, CSG_ROW); }
#endif
uniform float u_csg_tie;               // the tie rule's length, world units (tie_length)
uniform int u_csg_nodes;               // hierarchy nodes
uniform int u_csg_start;               // the nodes to look through for the leaves a ray
                                       // starts in: 0 where none can hold a ray's start
uniform int u_csg_ops;                 // tree program codes
uniform int u_csg_bvh;                 // first texel of the hierarchy
uniform int u_csg_program;             // first texel of the program (code, first record)
uniform int u_csg_records;             // first texel of the skip records
                                       // (end position, first leaf, last leaf, next)
uniform int u_csg_table;               // first texel of the truth table (16 bits a
                                       // component), or -1: the tree runs as its program

// leaf k: texels 8k .. 8k+7: inverse rows 0-2, normal matrix rows 3-5 (kind in 3.w),
// params 6
vec3 to_leaf(int k, vec4 p) {
    return vec3(dot(csg_texel(8 * k), p), dot(csg_texel(8 * k + 1), p),
                dot(csg_texel(8 * k + 2), p));
}
vec3 normal_to_world(int k, vec3 n) {
    return vec3(dot(csg_texel(8 * k + 3).xyz, n), dot(csg_texel(8 * k + 4).xyz, n),
                dot(csg_texel(8 * k + 5).xyz, n));
}
vec4 leaf_param(int k) { return csg_texel(8 * k + 6); }
int leaf_kind(int k) { return int(csg_texel(8 * k + 3).w); }
