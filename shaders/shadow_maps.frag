#version 410 core
// Shadow maps looked up for a G-buffer where the GL has no compute shaders (OpenGL 4.1:
// every Mac): shadow_maps.comp's work as a fragment program drawn over the viewport, one
// light's map a draw (its arrays hold that one light); render/passes/shadows.py copies
// what it writes into the light's layer of the visibility array.
#include "gbuffer_point.glsl"
#include "shadow_lookup.glsl"

layout(location = 0) out float out_visible;

void main() {
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec2 at = px - ivec2(u_viewport.xy);
    int face_id = texelFetch(u_face_ids, px, 0).r;
    if (face_id == 0) {
        out_visible = 1.0;
        return;
    }
    float depth = uintBitsToFloat(texelFetch(u_depth_bits, px, 0).r);
    vec3 to_eye;
    vec3 p = gbuffer_point(at, depth, to_eye);
    vec3 n = normalize(texelFetch(u_normals, px, 0).xyz * 2.0 - 1.0);
    // (the bias wants the surface's slope against the light: the polygon's own plane)
    n = gbuffer_plane_normal(at, p, face_id, n);
    out_visible = map_visibility(0, p, n, to_eye);
}
