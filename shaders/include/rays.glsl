// A pixel's ray, the GPU's side of Camera.rays: from the near plane's point at ``ndc`` to
// the far plane's, through the inverse of the view-projection matrix. ``origin`` is on the
// near plane (world), ``span`` runs to the far plane (not unit: normalize it for a unit
// direction; kept whole, it is affine in ndc, so it interpolates exactly).
#ifndef RAYS_GLSL
#define RAYS_GLSL
void pixel_ray(mat4 inverse_view_proj, vec2 ndc, out vec3 origin, out vec3 span) {
    vec4 a = inverse_view_proj * vec4(ndc, -1.0, 1.0);
    vec4 b = inverse_view_proj * vec4(ndc, 1.0, 1.0);
    origin = a.xyz / a.w;
    span = b.xyz / b.w - origin;
}
#endif
