#version 330 core
// The scene's sky where nothing is drawn (render/passes/environment.py): each pixel's view
// direction looked up in the equirectangular map (environment_map.glsl), as the path
// tracer's camera rays that leave the scene see it -- the texel's radiance, not a blend.
#include "environment_map.glsl"
#include "srgb.glsl"

uniform sampler2D u_env_background;
uniform mat4 u_inverse_view_proj;  // clip to world
uniform vec2 u_viewport_origin, u_viewport_size;
uniform float u_env_rotation, u_env_intensity;
out vec4 f_color;

void main() {
    vec2 ndc = 2.0 * (gl_FragCoord.xy - u_viewport_origin) / u_viewport_size - 1.0;
    vec4 a = u_inverse_view_proj * vec4(ndc, -1.0, 1.0);
    vec4 b = u_inverse_view_proj * vec4(ndc, 1.0, 1.0);
    vec3 d = normalize(b.xyz / b.w - a.xyz / a.w);
    vec3 c = u_env_intensity *
             texture(u_env_background, env_map_uv(env_map_frame(d, u_env_rotation))).rgb;
#ifdef SRGB
    c = encode_srgb(c);
#endif
    f_color = vec4(c, 1.0);
}
