#version 430 core
// Exact cast shadows: for each pixel's nearest surface point (from a G-buffer the renderer
// drew: view depth and polygon id) and each light (the z of the invocation), one ray to the
// light through a BVH of the scene's world triangles (shadow_trace.glsl); any hit before
// the light hides it. One invocation is one ray, its loop iterations counted and bounded:
// a ray that runs out is counted in `undecided` and its light shown as seen.
// CSG_SOLID: this run casts against one CSG solid instead (csg.glsl, the raster pass's
// cast, from the ray's start moved eps towards the light), and only hides more: a light a
// run before found hidden stays hidden (one run a solid, after the triangles').
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

#include "shadow_trace.glsl"
#ifdef CSG_SOLID
layout(r8, binding = BINDING_VISIBILITY_IMAGE) uniform image2DArray u_visibility;
int g_iter;
#define CSG_COUNT ++g_iter
#include "csg.glsl"
#else
layout(r8, binding = BINDING_VISIBILITY_IMAGE) writeonly uniform image2DArray u_visibility;
#endif

#include "gbuffer_point.glsl"
uniform int u_light_count;

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
    float depth = uintBitsToFloat(texelFetch(u_depth_bits, px, 0).r);
    vec3 to_eye;
    vec3 p = gbuffer_point(id.xy, depth, to_eye);
    vec4 l = u_shadow_lights[light];
    vec3 shading_n = texelFetch(u_normals, px, 0).xyz * 2.0 - 1.0;
    int seen = 1;
    if (face != 0) {
#ifdef CSG_SOLID
        if (l.w > 1.5) return;
        ShadowRay r = shadow_ray(p, depth, l, face - 1, shading_n, to_eye);
        float t;
        g_iter = 0;
        int leaf = csg_first_hit(r.o + r.eps * r.d, r.d, t);
        seen = leaf >= 0 && t > 0.0 && t < r.dist - 2.0 * r.eps ? 0 : 1;
        if (g_iter > u_budget) seen = -1;  // (counted as the walk went: flagged, not hidden)
        if (seen == 1) return;  // (the triangles' answer stands)
#else
        seen = light_seen(p, depth, l, face - 1, shading_n, to_eye);
#endif
        if (seen < 0) {
            atomicAdd(undecided, 1u);
        }
    }
    imageStore(u_visibility, ivec3(px, light), vec4(seen == 0 ? 0.0 : 1.0));
}
