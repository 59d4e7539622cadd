// Cast shadows in a fragment stage: a shadow pass (render/passes/shadows.py) left, for
// this pixel's nearest surface point, how much of each light reaches it (1 seen, 0 hidden;
// a shadow map's PCF gives fractions), one layer of u_visibility per light. Include it
// before lighting.glsl: its LIGHT_VISIBLE weighs each light's term.
#ifndef SHADOW_MASK_GLSL
#define SHADOW_MASK_GLSL
#ifdef SHADOW_MASK
#if defined(SHADOW_MAPS_FORWARD) || defined(SHADOW_RAYS_FORWARD)
uniform mat4 u_camera_to_world;
#define HAS_CAMERA_TO_WORLD
// The direction from world point p towards the eye: the view's backward axis everywhere
// for an orthographic camera.
vec3 towards_eye(vec3 p) {
#ifdef ORTHOGRAPHIC
    return u_camera_to_world[2].xyz;
#else
    return u_camera_to_world[3].xyz - p;
#endif
}
#endif
#ifdef SHADOW_MAPS_FORWARD
// Without a visibility array: the fragment looks each light's shadow map up itself, once,
// at its own surface point (SHADOW_PREPARE, called by the program's main before lighting).
#define SHADOW_LIGHTS LIGHT_COUNT
#include "shadow_lookup.glsl"
float g_visible[LIGHT_COUNT];

void shadow_prepare(vec3 p_view, vec3 n_world) {
    vec3 p = (u_camera_to_world * vec4(p_view, 1.0)).xyz;
    // (the bias wants the surface's slope against the light: the triangle's own plane,
    // not the shading normal of a smooth mesh)
    vec3 plane = cross(dFdx(p), dFdy(p));
    vec3 n = dot(plane, plane) > 0.0 ? normalize(plane) : normalize(n_world);
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        g_visible[i] = map_visibility(i, p, n, towards_eye(p));
    }
}
#define SHADOW_PREPARE(p_view, n_world) shadow_prepare(p_view, n_world)
#define LIGHT_VISIBLE(i) g_visible[i]
#elif defined(SHADOW_RAYS_FORWARD)
// Without a visibility array: the fragment traces a ray to each light itself, from its own
// surface point (shadow_trace.glsl; SHADOW_PREPARE, called by the program's main before
// lighting). Its rays' loop iterations share one budget (the pass divides it). The depth
// test runs first (a hidden fragment traces nothing; the count of rays that ran out is a
// storage-buffer write, which would otherwise keep the test late).
layout(early_fragment_tests) in;
#include "shadow_trace.glsl"
#ifdef SHADOW_OWN_POLYGON
// (the includer says which of the scene's polygons its surface is: a point is none)
#elif defined(PATCH_IDS)
#define SHADOW_OWN_POLYGON -2  // (a patch's triangles are no mesh polygon's)
#else
#ifndef POLYGON_ID_IN
#define POLYGON_ID_IN
#ifdef INSTANCED
#include "instances.glsl"
#define u_face_id_base instance_face_base()
#else
uniform int u_face_id_base;
#endif
#ifdef POLYGON_FETCH
#include "polygon_fetch.glsl"
#define v_polygon polygon_of(gl_PrimitiveID)
#else
flat in int v_polygon;  // this mesh's polygon (polygon_id.glsl)
#endif
#endif
#define SHADOW_OWN_POLYGON (u_face_id_base + v_polygon)
#endif
float g_visible[LIGHT_COUNT];

void shadow_prepare(vec3 p_view, vec3 n_world) {
    vec3 p = (u_camera_to_world * vec4(p_view, 1.0)).xyz;
    vec3 to_eye = towards_eye(p);
    vec3 n = normalize(n_world);
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        int seen = light_seen(p, -p_view.z, u_shadow_lights[i], SHADOW_OWN_POLYGON, n, to_eye);
        if (seen < 0) {
            atomicAdd(undecided, 1u);
        }
        g_visible[i] = seen == 0 ? 0.0 : 1.0;
    }
}
#define SHADOW_PREPARE(p_view, n_world) shadow_prepare(p_view, n_world)
#define LIGHT_VISIBLE(i) g_visible[i]
#else
uniform sampler2DArray u_visibility;
#define LIGHT_VISIBLE(i) texelFetch(u_visibility, ivec3(ivec2(gl_FragCoord.xy), i), 0).r
#define SHADOW_PREPARE(p_view, n_world)
#endif

// The ambient term and the terms of the lights this pixel's point sees (flat and Gouraud:
// the terms were made at the corners, light by light).
vec3 visible_sum(vec3 ambient, vec3 terms[LIGHT_COUNT]) {
    vec3 color = ambient;
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        color += LIGHT_VISIBLE(i) * terms[i];
    }
    return color;
}
#else
#define SHADOW_PREPARE(p_view, n_world)
#endif
#endif
