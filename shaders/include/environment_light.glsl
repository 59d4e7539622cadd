// glTF's model lit by the scene's sky (ENVIRONMENT_LIGHT; scene/environment.py builds the
// tables, render/passes/environment.py binds them) by the split-sum approximation:
//   (F0 A + B) x the sky prefiltered by the GGX lobe about the mirror direction
//   + (1 - metallic) base (1 - (F0 A_d + B_d)) x the irradiance's mean radiance,
// A, B the specular lobe's directional albedo split by Schlick's Fresnel, A_d, B_d the
// diffuse lobe's (1 - F) -- radiance, as pbr.glsl's other terms.
#ifndef ENVIRONMENT_LIGHT_GLSL
#define ENVIRONMENT_LIGHT_GLSL
#include "environment_map.glsl"

uniform sampler2D u_env_specular;    // level k: roughness k / (levels - 1)
uniform sampler2D u_env_irradiance;  // irradiance / pi
uniform sampler2D u_env_split_sum;   // (A, B, A_d, B_d) at (N.V, roughness)
uniform float u_env_levels;
uniform mat3 u_env_basis;            // view directions to the map's frame

vec3 environment_light(vec3 n_view, vec3 v_view, vec3 base, float metallic,
                       float roughness) {
    vec3 n = u_env_basis * n_view, v = u_env_basis * v_view;
    float nv = clamp(dot(n, v), 1e-4, 1.0);
    vec2 size = vec2(textureSize(u_env_split_sum, 0));  // (ends at its texel centres)
    vec4 split = texture(u_env_split_sum, (vec2(nv, roughness) * (size - 1.0) + 0.5) / size);
    vec3 f0 = mix(vec3(0.04), base, metallic);
    vec3 lobe = textureLod(u_env_specular, env_map_uv(reflect(-v, n)),
                           roughness * (u_env_levels - 1.0)).rgb;
    vec3 sky = textureLod(u_env_irradiance, env_map_uv(n), 0.0).rgb;
    return (f0 * split.x + split.y) * lobe +
           (1.0 - metallic) * base * (1.0 - (f0 * split.z + split.w)) * sky;
}
#endif
