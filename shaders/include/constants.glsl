// The per-draw constants of the lighting formula, and where a program reads them from.
//
// The products that are constant over a draw are made once per model on the CPU (same
// formula, fewer multiplies per pixel): Ia ka C, Ip kd C and Ip ks per light, with n and
// each light's position (or direction) and attenuation.
//
// They are uniforms, except in the fragment stage of a per-pixel program compiled with
// FLAT_CONSTANTS: there they arrive as flat inputs that the vertex stage copied from the
// uniforms (forward_constants(); a vertex stage asks for it with FORWARD_CONSTANTS). On a
// software rasterizer (llvmpipe) every uniform component a fragment program reads is a
// guarded load repeated for each block of pixels, while a flat input is set up once per
// triangle: measured at 512x512, three uniform floats cost about 3% of a Phong frame. On a
// GPU uniforms are free, so only software renderers compile this way. The values are the
// same bits either way (a flat input is not interpolated).

#define MAX_LIGHTS 8
#define DIRECTIONAL 0
#define POINT 1
#define ATTENUATED 2
#define SPOT 3  // (a point light in a cone, with its attenuation: lighting.glsl)
#ifndef LIGHT_COUNT
#define LIGHT_COUNT 1
#define LIGHT_KINDS POINT
#endif
#include "surface_color.glsl"

#if defined(FLAT_CONSTANTS) && !defined(FORWARD_CONSTANTS)
flat in vec4 k_ambient_shininess;               // (Ia ka C, n)
flat in vec4 k_light_pos_view[LIGHT_COUNT];
flat in vec3 k_light_diffuse[LIGHT_COUNT];
flat in vec3 k_light_specular[LIGHT_COUNT];
#ifdef ANY_ATTENUATED
flat in vec3 k_light_attenuation[LIGHT_COUNT];
#define LIGHT_ATTENUATION(i) k_light_attenuation[i]
#else
#define LIGHT_ATTENUATION(i) vec3(1.0, 0.0, 0.0)
#endif
#ifdef ANY_SPOT
flat in vec4 k_light_spot[LIGHT_COUNT];
#define LIGHT_SPOT(i) k_light_spot[i]
#else
#define LIGHT_SPOT(i) vec4(0.0)
#endif
#ifdef VERTEX_COLORS  // (the pixel's C times the constants: surface_color.glsl)
#define AMBIENT_TERM (k_ambient_shininess.xyz * SURFACE_C)
#define LIGHT_DIFFUSE(i) (k_light_diffuse[i] * SURFACE_C)
#else
#define AMBIENT_TERM k_ambient_shininess.xyz
#define LIGHT_DIFFUSE(i) k_light_diffuse[i]
#endif
#define SHININESS k_ambient_shininess.w
#define LIGHT_POS_VIEW(i) k_light_pos_view[i]
#define LIGHT_SPECULAR(i) k_light_specular[i]

#else
uniform vec3 u_light_specular[MAX_LIGHTS];     // Ip ks
uniform float u_shininess;                     // n
uniform vec4 u_light_pos_view[MAX_LIGHTS];     // point: position; directional: unit vector TO it
uniform vec3 u_light_attenuation[MAX_LIGHTS];  // (constant, linear, quadratic)
uniform vec4 u_light_spot[MAX_LIGHTS];         // a spot's axis x cone scale, cone offset
#ifdef INSTANCED  // (an instance's colour is its own: its row, instances.glsl)
#include "instances.glsl"
#ifdef VERTEX_COLORS
#define AMBIENT_TERM (instance_ambient() * SURFACE_C)
#define LIGHT_DIFFUSE(i) (instance_diffuse(i) * SURFACE_C)
#else
#define AMBIENT_TERM instance_ambient()
#define LIGHT_DIFFUSE(i) instance_diffuse(i)
#endif
#elif defined(POINT_COLORS)  // (a cloud's colour is each point's own: points.frag)
uniform vec3 u_ambient_term;                   // Ia ka (C = 1 where C is the point's)
uniform vec3 u_light_diffuse[MAX_LIGHTS];      // Ip kd (likewise)
uniform vec2 u_color_weight;                   // 1: the product takes the point's colour
flat in vec3 f_color;
#define AMBIENT_TERM (u_ambient_term * mix(vec3(1.0), f_color, u_color_weight.x))
#define LIGHT_DIFFUSE(i) (u_light_diffuse[i] * mix(vec3(1.0), f_color, u_color_weight.y))
#else
uniform vec3 u_ambient_term;                   // Ia ka C
uniform vec3 u_light_diffuse[MAX_LIGHTS];      // Ip kd C
#ifdef VERTEX_COLORS  // (times the mesh's C at the point lit: surface_color.glsl)
#define AMBIENT_TERM (u_ambient_term * SURFACE_C)
#define LIGHT_DIFFUSE(i) (u_light_diffuse[i] * SURFACE_C)
#else
#define AMBIENT_TERM u_ambient_term
#define LIGHT_DIFFUSE(i) u_light_diffuse[i]
#endif
#endif
#define SHININESS u_shininess
#define LIGHT_POS_VIEW(i) u_light_pos_view[i]
#define LIGHT_SPECULAR(i) u_light_specular[i]
#define LIGHT_ATTENUATION(i) u_light_attenuation[i]
#define LIGHT_SPOT(i) u_light_spot[i]

#ifdef FORWARD_CONSTANTS
flat out vec4 k_ambient_shininess;
flat out vec4 k_light_pos_view[LIGHT_COUNT];
flat out vec3 k_light_diffuse[LIGHT_COUNT];
flat out vec3 k_light_specular[LIGHT_COUNT];
#ifdef ANY_ATTENUATED
flat out vec3 k_light_attenuation[LIGHT_COUNT];
#endif
#ifdef ANY_SPOT
flat out vec4 k_light_spot[LIGHT_COUNT];
#endif

void forward_constants() {
    // (a vertex stage that forwards never sets the surface colour: the constants go on
    // without it, and the fragment stage multiplies in the pixel's)
    k_ambient_shininess = vec4(AMBIENT_TERM, u_shininess);
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        k_light_pos_view[i] = u_light_pos_view[i];
        k_light_diffuse[i] = LIGHT_DIFFUSE(i);
        k_light_specular[i] = u_light_specular[i];
#ifdef ANY_ATTENUATED
        k_light_attenuation[i] = u_light_attenuation[i];
#endif
#ifdef ANY_SPOT
        k_light_spot[i] = u_light_spot[i];
#endif
    }
}
#endif
#endif
