// A pixel's ray, the GPU's side of Camera.rays: from the near plane's point at ``ndc`` to
// the far plane's. Unprojected in view space (``inverse_proj``: clip -> view), then moved
// to the world (``camera_to_world``, the inverse of the rigid view matrix): in view space
// the rounding of the far point's w (a difference of two terms of size 1/near, large when
// the near plane is tiny) scales it about the eye, along its own ray, where through the
// whole inverse view-projection it moves it about the world's origin, off the ray.
// ``origin`` is on the near plane (world), ``span`` runs to the far plane (not unit:
// normalize it for a unit direction; kept whole, it is affine in ndc, so it interpolates
// exactly).
#ifndef RAYS_GLSL
#define RAYS_GLSL
void pixel_ray(mat4 inverse_proj, mat4 camera_to_world, vec2 ndc, out vec3 origin,
               out vec3 span) {
    vec4 a = inverse_proj * vec4(ndc, -1.0, 1.0);
    vec4 b = inverse_proj * vec4(ndc, 1.0, 1.0);
    vec3 near_point = a.xyz / a.w;
    origin = (camera_to_world * vec4(near_point, 1.0)).xyz;
    span = mat3(camera_to_world) * (b.xyz / b.w - near_point);
}
#endif
