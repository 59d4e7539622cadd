#version 430 core
// Shadow maps, looked up for a G-buffer (the draw's visibility array read back as
// Frame.visibility): for each pixel's surface point (the G-buffer's view depth and world
// normal), how much of one light its depth map says reaches it (shadow_lookup.glsl; its
// arrays hold this one light). Draws that need no visibility array look the maps up as
// they shade instead (SHADOW_MAPS_FORWARD, shadow_mask.glsl).
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(r8, binding = BINDING_VISIBILITY_IMAGE) writeonly uniform image2DArray u_visibility;
uniform int u_layer;               // the light's layer of u_visibility

#include "gbuffer_point.glsl"
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
    vec3 to_eye;
    vec3 p = gbuffer_point(id.xy, depth, to_eye);
    vec3 n = normalize(texelFetch(u_normals, px, 0).xyz * 2.0 - 1.0);
    // (the bias wants the surface's slope against the light: the polygon's own plane)
    n = gbuffer_plane_normal(id.xy, p, face_id, n);
    imageStore(u_visibility, ivec3(px, u_layer), vec4(map_visibility(0, p, n, to_eye)));
}
