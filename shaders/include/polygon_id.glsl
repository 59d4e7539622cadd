// The polygon id of the id output (outputs.glsl) and of a fragment's own shadow rays
// (shadow_mask.glsl, SHADOW_RAYS_FORWARD), for a mesh program's vertex stage: each
// corner of a triangle carries its polygon's id (such draws share no vertices between
// triangles: render/gpu_mesh.py), passed on flat. Reading gl_PrimitiveID in the fragment
// stage instead cost llvmpipe 4 ms of a 100k-triangle draw that took 8 without it.
// An instanced draw's vertex stage also hands its instance on (instances.glsl).
#ifdef INSTANCED
#include "instances.glsl"
#define PASS_INSTANCE() v_instance = gl_InstanceID
#else
#define PASS_INSTANCE()
#endif
#if (defined(GLSHADE_AUX_OUTPUTS) || defined(SHADOW_RAYS_FORWARD)) && \
    !defined(POLYGON_FETCH) && !defined(FLAT_FETCH)
// (a big mesh's draw finds its polygons per triangle instead: polygon_fetch.glsl)
in int in_polygon;
flat out int v_polygon;
#define PASS_POLYGON_ID() v_polygon = in_polygon; PASS_INSTANCE()
#else
#define PASS_POLYGON_ID() PASS_INSTANCE()
#endif
