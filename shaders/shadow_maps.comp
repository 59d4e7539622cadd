#version 430 core
// Shadow maps, looked up for a G-buffer (the draw's visibility array read back as
// Frame.visibility): for each pixel's surface point (the G-buffer's view depth and world
// normal), how much of one light its depth map says reaches it (shadow_lookup.glsl; its
// arrays hold this one light). Draws that need no visibility array look the maps up as
// they shade instead (SHADOW_MAPS_FORWARD, shadow_mask.glsl).
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(r8, binding = 0) writeonly uniform image2DArray u_visibility;
uniform isampler2D u_face_ids;
uniform usampler2D u_depth_bits;
uniform sampler2D u_normals;       // world normal as (n + 1) / 2
uniform mat4 u_inverse_proj;     // clip -> view (rays.glsl)
uniform mat4 u_camera_to_world; // view -> world
uniform vec4 u_viewport;
uniform vec3 u_eye;
uniform vec3 u_forward;
uniform float u_near;
uniform int u_layer;               // the light's layer of u_visibility

#include "rays.glsl"
#include "shadow_lookup.glsl"

void main() {
    ivec3 id = ivec3(gl_GlobalInvocationID);
    ivec2 px = id.xy + ivec2(u_viewport.xy);
    if (any(greaterThanEqual(id.xy, ivec2(u_viewport.zw)))) return;
    int face_id = texelFetch(u_face_ids, px, 0).r;
    if (face_id == 0) {
        imageStore(u_visibility, ivec3(px, u_layer), vec4(1.0));
        return;
    }
    float depth = uintBitsToFloat(texelFetch(u_depth_bits, px, 0).r);
    vec2 ndc = (vec2(px) + 0.5 - u_viewport.xy) / u_viewport.zw * 2.0 - 1.0;
    vec3 origin, span;
    pixel_ray(u_inverse_proj, u_camera_to_world, ndc, origin, span);
    vec3 dir = normalize(span);
#ifdef ORTHOGRAPHIC
    vec3 p = origin + dir * (depth - u_near);
#else
    vec3 p = u_eye + dir * (depth / dot(dir, u_forward));
#endif
    vec3 n = normalize(texelFetch(u_normals, px, 0).xyz * 2.0 - 1.0);
    imageStore(u_visibility, ivec3(px, u_layer), vec4(map_visibility(0, p, n)));
}
