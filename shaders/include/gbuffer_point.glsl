// A G-buffer's surface point, for the compute passes that shade it (shadow_rays.comp,
// shadow_maps.comp; render/passes/shadows.py binds the G-buffer and sets the uniforms):
// rebuilt from the pixel's view depth along its ray, which is affine in the pixel
// (geometry/transforms.py, pixel_rays: computed in float64, two fused multiply-adds a
// pixel where unprojecting costs three matrix products).
#ifndef GBUFFER_POINT_GLSL
#define GBUFFER_POINT_GLSL
uniform isampler2D u_face_ids;     // polygon id + 1 (0: background), the G-buffer's
uniform usampler2D u_depth_bits;   // floatBitsToUint(view depth)
uniform sampler2D u_normals;       // world normal as (n + 1) / 2 (the shading one, seen side)
// a pixel's ray: its origin and span at the viewport's first pixel and a pixel's steps
uniform vec3 u_origin0, u_origin_dx, u_origin_dy;
uniform vec3 u_span0, u_span_dx, u_span_dy;
uniform vec4 u_viewport;           // x, y, w, h of the draw in the G-buffer's pixels
uniform vec3 u_eye;
uniform vec3 u_forward;            // the view axis (world, unit)
uniform float u_near;

// the world point at view depth ``depth`` on the ray of the viewport's pixel ``at``, and
// the direction towards the eye from it
vec3 gbuffer_point(ivec2 at, float depth, out vec3 to_eye) {
    vec2 a = vec2(at);
#ifdef ORTHOGRAPHIC
    to_eye = -u_forward;
    return u_origin0 + a.x * u_origin_dx + a.y * u_origin_dy + u_forward * (depth - u_near);
#else
    vec3 span = u_span0 + a.x * u_span_dx + a.y * u_span_dy;
    vec3 p = u_eye + span * (depth / dot(span, u_forward));
    to_eye = u_eye - p;
    return p;
#endif
}
#endif
