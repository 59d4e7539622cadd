// CSG by ray casting with the tree as data (solids/encoding.py makes it, render/passes/csg.py
// uploads it), by concern: where the data is and how it is read; the leaves; the walk of a
// larger tree; the one-step cast of a small one (and csg_first_hit, csg_normal).
#include "csg/layout.glsl"
#include "csg/leaves.glsl"
#include "csg/walk.glsl"
#include "csg/onestep.glsl"
