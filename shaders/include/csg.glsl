// CSG by ray casting with the tree as data (solids/encoding.py makes it, render/passes/csg.py
// uploads it), by concern: where the data is and how it is read; the leaves; the walk of a
// larger tree (its csg_first_hit); the one-step cast of a small one (its csg_first_hit);
// and, here, the surface's normal either way.
#include "csg/layout.glsl"
#include "csg/leaves.glsl"
#include "csg/walk.glsl"
#include "csg/onestep.glsl"

// the surface's normal at p (world), outward from the solid
vec3 csg_normal(int k, vec3 p) {
#ifdef CSG_SLOTS
    // (from the hit's slot: its rows are the world -> leaf map, whose transpose takes a
    // gradient back to world; the sign is the caller's: it turns the normal to the eye)
    int s = csg_hit_slot;
    vec4 m0 = u_csg_slot[4 * s], m1 = u_csg_slot[4 * s + 1], m2 = u_csg_slot[4 * s + 2];
    vec4 p1 = vec4(p, 1.0);
    vec3 g = leaf_gradient(csg_hit_kind, u_csg_slot[4 * s + 3],
                           vec3(dot(m0, p1), dot(m1, p1), dot(m2, p1)));
    return g.x * m0.xyz + g.y * m1.xyz + g.z * m2.xyz;
#else
    return normal_to_world(k, leaf_gradient(leaf_kind(k), leaf_param(k),
                                            to_leaf(k, vec4(p, 1.0))));
#endif
}
