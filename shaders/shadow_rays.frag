#version 330 core
// Exact cast shadows where the GL has no compute shaders (OpenGL 4.1 and older: every
// Mac): shadow_rays.comp's work as a fragment program, drawn over the viewport once a
// light (u_light), the hierarchy read from textures (SHADOW_TEXELS in shadow_trace.glsl).
// The same ray from the same point through the same walk: the same visibility, bit for
// bit. It writes the light's visibility (render/passes/shadows.py copies it into the
// array's layer) and flags a ray that ran out of its budget (the pass counts the flags).
// CSG_SOLID: this draw casts against one CSG solid instead, and only hides more: it reads
// the visibility so far (u_previous) and writes it on where the solid hides nothing.
#include "shadow_trace.glsl"
#ifdef CSG_SOLID
uniform sampler2DArray u_previous;
int g_iter;
#define CSG_COUNT ++g_iter
#include "csg.glsl"
#endif
#include "gbuffer_point.glsl"
uniform int u_light;

layout(location = 0) out float out_visible;
layout(location = 1) out float out_undecided;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec2 at = px - ivec2(u_viewport.xy);
    int face = texelFetch(u_face_ids, px, 0).r;
    out_undecided = 0.0;
    out_visible = 1.0;
#ifdef CSG_SOLID
    out_visible = texelFetch(u_previous, ivec3(px, u_light), 0).r;
    if (face == 0 || out_visible == 0.0) return;
#endif
    float depth = uintBitsToFloat(texelFetch(u_depth_bits, px, 0).r);
    vec3 to_eye;
    vec3 p = gbuffer_point(at, depth, to_eye);
    vec4 l = u_shadow_lights[u_light];
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
        out_undecided = seen < 0 ? 1.0 : 0.0;
    }
    out_visible = seen == 0 ? 0.0 : 1.0;
}
