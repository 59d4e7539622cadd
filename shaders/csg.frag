#version 330 core
// CSG solids by ray casting: the ray through this pixel (from the near plane), the tree's
// events along it, the first surface beyond the near plane; its depth goes to
// gl_FragDepth, so solids and meshes meet in one z-buffer. Lit by the same function as the
// meshes (lighting.glsl) with the exact normal at every pixel.
#include "shadow_mask.glsl"
#include "lighting.glsl"
#include "csg.glsl"

uniform mat4 u_inverse_proj;     // clip -> view (rays.glsl)
#ifndef HAS_CAMERA_TO_WORLD
uniform mat4 u_camera_to_world; // view -> world
#endif
uniform mat4 u_solid_view_proj;  // world -> clip (the box's own is the vertex stage's)
uniform mat4 u_view;
uniform mat3 u_view_normal;        // world -> view, for normals (the view is rigid)
uniform vec2 u_viewport_origin;
uniform vec2 u_viewport_size;
uniform int u_face_id_base;
uniform vec2 u_depth_range;

#ifdef CSG_SLOTS
noperspective in vec3 v_ray_origin;
noperspective in vec3 v_ray_span;
#endif

layout(location = 0) out vec4 frag_color;
#ifdef GLSHADE_AUX_OUTPUTS
layout(location = 1) out vec4 frag_normal;
layout(location = 2) out int frag_face_id;
layout(location = 3) out uint frag_depth_bits;
#endif

#ifdef FLAT_FACES
// Flat shading: a planar leaf face is lit once, at its centre (as a mesh polygon at its
// centroid); a curved face has no centre and is lit where the ray hits it.
vec3 face_centre(int i, vec3 p_world) {
    vec3 p = to_leaf(i, vec4(p_world, 1.0));
    vec4 q = leaf_param(i);
    int kind = leaf_kind(i);
    vec3 c;
    if (IS(kind, 1)) {                       // box: the face of the largest p / h
        vec3 r = abs(p / q.xyz);
        c = r.x >= r.y && r.x >= r.z ? vec3(sign(p.x) * q.x, 0.0, 0.0) :
            r.y >= r.z ? vec3(0.0, sign(p.y) * q.y, 0.0) : vec3(0.0, 0.0, sign(p.z) * q.z);
    } else if (IS(kind, 2) && abs(abs(p.y) - q.y) < abs(length(p.xz) - q.x)) {
        c = vec3(0.0, sign(p.y) * q.y, 0.0);   // a cylinder's cap
    } else if (IS(kind, 3) && abs(p.y + q.y) < abs(length(p.xz) - q.z * (q.y - p.y))) {
        c = vec3(0.0, -q.y, 0.0);              // a cone's base
    } else {
        return p_world;
    }
    mat4 m = transpose(mat4(csg_texel(8 * i), csg_texel(8 * i + 1), csg_texel(8 * i + 2),
                            vec4(0.0, 0.0, 0.0, 1.0)));
    vec4 w = inverse(m) * vec4(c, 1.0);
    return w.xyz / w.w;
}
#endif

#include "srgb.glsl"
#include "rays.glsl"

void main() {
#ifdef CSG_SLOTS
    // (near plane to far plane, interpolated: csg.vert)
    vec3 ro = v_ray_origin, rd = v_ray_span;
#else
    vec2 ndc = (gl_FragCoord.xy - u_viewport_origin) / u_viewport_size * 2.0 - 1.0;
    vec3 ro, rd;
    pixel_ray(u_inverse_proj, u_camera_to_world, ndc, ro, rd);
    rd = normalize(rd);
#endif
    float t;
    int leaf = csg_first_hit(ro, rd, t);
    if (leaf < 0) discard;
    vec3 p = ro + t * rd;
    vec4 clip = u_solid_view_proj * vec4(p, 1.0);
    float z = clip.z / clip.w;
    if (z > 1.0) discard;  // beyond the far plane
    gl_FragDepth = 0.5 * z + 0.5;
    vec3 n_world = normalize(csg_normal(leaf, p));
    vec3 p_view = (u_view * vec4(p, 1.0)).xyz;
    vec3 n_view = normalize(u_view_normal * n_world);
    vec3 v = view_dir(p_view);
    if (dot(n_view, v) < 0.0) {  // seen from inside the solid: the surface faces the eye
        n_view = -n_view;
        n_world = -n_world;
    }
    SHADOW_PREPARE(p_view, n_world);
#if defined(SHOW_NORMALS)
    vec3 color = 0.5 * n_world + 0.5;
#elif defined(SHOW_DEPTH)
    vec3 color = vec3(1.0 - clamp((-p_view.z - u_depth_range.x) /
                                  (u_depth_range.y - u_depth_range.x), 0.0, 1.0));
#else
#ifdef FLAT_FACES
    vec3 centre_view = (u_view * vec4(face_centre(leaf, p), 1.0)).xyz;
    if (dot(n_view, view_dir(centre_view)) < 0.0) n_view = -n_view;  // (seen from inside)
    vec3 color = light_intensity(centre_view, n_view, view_dir(centre_view));
#else
    vec3 color = light_intensity(p_view, n_view, v);
#endif
#endif
    color = clamp(color, 0.0, 1.0);
#ifdef SRGB
    color = encode_srgb(color);
#endif
    frag_color = vec4(color, 1.0);
#ifdef GLSHADE_AUX_OUTPUTS
    frag_normal = vec4(n_world, 1.0);
    frag_face_id = u_face_id_base + leaf + 1;
    frag_depth_bits = floatBitsToUint(-p_view.z);
#endif
}
