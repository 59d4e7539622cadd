#version 330 core
// A point cloud's point (render/passes/points.py), lit by the meshes' formula
// (lighting.glsl). A sphere or disc casts the pixel's ray (from the near plane, view space)
// and writes its hit's depth to gl_FragDepth, so points and meshes meet in one z-buffer; a
// square is flat at its centre's depth and takes the rasterised one. Phong and Gouraud
// light every pixel at its own point and normal (a point has no vertices to light); flat
// lights a point once: a sphere at its point nearest the eye, a disc or square at its
// centre. A square's normal is its point's (else it faces the eye).
#define SHADOW_OWN_POLYGON -2  // (a point is none of the triangles that cast shadows)
#include "shadow_mask.glsl"
#include "lighting.glsl"
#include "srgb.glsl"

uniform mat4 u_inverse_proj;        // clip -> view
#ifndef HAS_CAMERA_TO_WORLD
uniform mat4 u_camera_to_world;     // view -> world (normals out)
#endif
uniform vec2 u_viewport_origin;
uniform vec2 u_viewport_size;
uniform mat4 u_proj;
uniform int u_face_id_base;
uniform vec2 u_depth_range;
uniform vec3 u_emission;            // the radiosity mode's display: emission + ambient

flat in vec3 f_centre;              // view space
flat in float f_radius;             // view units
flat in int f_index;
#ifdef POINT_NORMALS
flat in vec3 f_normal;              // view space, unit
#endif

layout(location = 0) out vec4 frag_color;
#ifdef GLSHADE_AUX_OUTPUTS
layout(location = 1) out vec4 frag_normal;
layout(location = 2) out int frag_face_id;
layout(location = 3) out uint frag_depth_bits;
#endif

void main() {
    vec3 c = f_centre;
    float r = f_radius;
    vec3 p, n;
#ifdef STYLE_SQUARE
    p = c;
#ifdef POINT_NORMALS
    n = f_normal;
#else
    n = view_dir(c);
#endif
#else
    vec2 ndc = (gl_FragCoord.xy - u_viewport_origin) / u_viewport_size * 2.0 - 1.0;
    vec4 a = u_inverse_proj * vec4(ndc, -1.0, 1.0);
    vec4 b = u_inverse_proj * vec4(ndc, 1.0, 1.0);
    vec3 o = a.xyz / a.w;
    vec3 d = normalize(b.xyz / b.w - o);
    vec3 oc = o - c;
#ifdef STYLE_DISC
    float facing = dot(d, f_normal);
    if (abs(facing) < 1e-12) discard;
    float t = -dot(oc, f_normal) / facing;
    if (t < 0.0) discard;                      // before the near plane
    p = o + t * d;
    vec3 off = p - c;
    if (dot(off, off) > r * r) discard;
    n = facing < 0.0 ? f_normal : -f_normal;   // (the side the eye sees)
#else
    // the ray's nearest approach to the centre, then half the chord either way (stable:
    // no difference of two large squares)
    float along = dot(oc, d);
    vec3 q = oc - along * d;
    float h2 = r * r - dot(q, q);
    if (h2 < 0.0) discard;
    float h = sqrt(h2);
    float t = -along - h;
    bool inside = t < 0.0;                     // the near plane cuts the sphere here
    if (inside) t = -along + h;
    if (t < 0.0) discard;
    p = o + t * d;
    n = (p - c) / r;
    if (inside) n = -n;                        // (its inside faces the eye)
#endif
    vec4 clip = u_proj * vec4(p, 1.0);
    float z = clip.z / clip.w;
    if (z > 1.0) discard;                      // beyond the far plane
    gl_FragDepth = 0.5 * z + 0.5;
#endif
    vec3 n_world = mat3(u_camera_to_world) * n;
    SHADOW_PREPARE(p, n_world);
#if defined(SHOW_NORMALS)
    vec3 color = 0.5 * n_world + 0.5;
#elif defined(SHOW_DEPTH)
    vec3 color = vec3(1.0 - clamp((-p.z - u_depth_range.x) /
                                  (u_depth_range.y - u_depth_range.x), 0.0, 1.0));
#elif defined(SHOW_DISPLAY)
    vec3 color = u_emission + AMBIENT_TERM;
#elif defined(FLAT_FACES)
#if defined(STYLE_SQUARE) || defined(STYLE_DISC)
    vec3 color = light_intensity(c, n, view_dir(c));
#else
    vec3 toward = view_dir(c);
    vec3 near_point = c + r * toward;
    vec3 color = light_intensity(near_point, toward, view_dir(near_point));
#endif
#else
    vec3 color = light_intensity(p, n, view_dir(p));
#endif
    color = clamp(color, 0.0, 1.0);
#ifdef SRGB
    color = encode_srgb(color);
#endif
    frag_color = vec4(color, 1.0);
#ifdef GLSHADE_AUX_OUTPUTS
    frag_normal = vec4(normalize(n_world), 1.0);
    frag_face_id = u_face_id_base + f_index + 1;
    frag_depth_bits = floatBitsToUint(-p.z);
#endif
}
