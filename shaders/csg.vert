#version 330 core
// CSG solids: a screen polygon that holds the solid (glshade/solids/proxy.py), in NDC, so
// that only pixels whose rays may meet it run the fragment program -- each once.
in vec3 in_position;               // (x, y) NDC
#ifdef CSG_SLOTS
// A small tree: each pixel's ray -- from the near plane to the far plane, t in units of
// that span -- in the world and in each slot's own frame. At a fixed NDC depth a
// projection's inverse divides by a constant, so both are affine in the pixel's NDC:
// computed at the corners and interpolated without perspective, exactly, where the
// fragment program would spend a matrix product a slot on each.
uniform mat4 u_inverse_proj;     // clip -> view (rays.glsl)
uniform mat4 u_camera_to_world; // view -> world
#include "rays.glsl"
uniform vec4 u_csg_slot[4 * CSG_SLOTS];
noperspective out vec3 v_ray_origin;
noperspective out vec3 v_ray_span;
noperspective out vec3 v_slot_origin[CSG_SLOTS];
noperspective out vec3 v_slot_span[CSG_SLOTS];
#endif

void main() {
    gl_Position = vec4(in_position.xy, 0.0, 1.0);
#ifdef CSG_SLOTS
    vec3 ro, rd;
    pixel_ray(u_inverse_proj, u_camera_to_world, in_position.xy, ro, rd);
    v_ray_origin = ro;
    v_ray_span = rd;
    for (int s = 0; s < CSG_SLOTS; ++s) {
        vec4 m0 = u_csg_slot[4 * s], m1 = u_csg_slot[4 * s + 1], m2 = u_csg_slot[4 * s + 2];
        vec4 ro1 = vec4(ro, 1.0);
        v_slot_origin[s] = vec3(dot(m0, ro1), dot(m1, ro1), dot(m2, ro1));
        v_slot_span[s] = vec3(dot(m0.xyz, rd), dot(m1.xyz, rd), dot(m2.xyz, rd));
    }
#endif
}
