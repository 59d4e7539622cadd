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

// The plane of the polygon drawn at viewport pixel ``at`` (world point p, polygon id
// ``face_id``): its unit normal from the points of the pixels beside it on the same polygon
// (a polygon is flat; the stored shading normal is not its plane on a smooth mesh), or
// ``fallback`` where no such pixel lies beside it in x or in y. The sign is arbitrary.
vec3 gbuffer_plane_normal(ivec2 at, vec3 p, int face_id, vec3 fallback) {
    ivec2 origin = ivec2(u_viewport.xy), size = ivec2(u_viewport.zw);
    vec3 steps[2];
    bool found[2] = bool[2](false, false);
    for (int axis = 0; axis < 2; ++axis) {
        for (int side = 1; side >= -1 && !found[axis]; side -= 2) {
            ivec2 q = at + (axis == 0 ? ivec2(side, 0) : ivec2(0, side));
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            if (texelFetch(u_face_ids, origin + q, 0).r != face_id) continue;
            vec3 unused;
            float d = uintBitsToFloat(texelFetch(u_depth_bits, origin + q, 0).r);
            steps[axis] = (gbuffer_point(q, d, unused) - p) * float(side);
            found[axis] = true;
        }
    }
    vec3 c = found[0] && found[1] ? cross(steps[0], steps[1]) : vec3(0.0);
    return dot(c, c) > 0.0 ? normalize(c) : fallback;
}
#endif
