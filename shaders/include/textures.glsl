// A textured surface's maps (scene/texture.py), sampled at the interpolated texture
// coordinate -- perspective-correct: the rasterizer interpolates v_uv in 3D, not on screen.
// Colour maps are sRGB textures, decoded to linear light by the sampler before filtering;
// a map the material lacks is a 1x1 white texture (no branch per pixel).
#ifndef TEXTURES_GLSL
#define TEXTURES_GLSL
#ifdef NOTES_TEXTURED
uniform sampler2D u_map_diffuse;   // map_Kd: multiplies the ambient and diffuse terms
uniform sampler2D u_map_specular;  // map_Ks: multiplies the specular term
uniform sampler2D u_map_opacity;   // map_d: multiplies the opacity (red channel)
uniform vec4 u_map_st[3];          // each map's (scale u, v, offset u, v): MTL -s, -o

// The lit colour of a textured point: its two parts (lighting.glsl) times their maps.
vec3 textured_color(vec3 ambient_diffuse, vec3 specular, vec2 uv) {
    return ambient_diffuse * texture(u_map_diffuse, uv * u_map_st[0].xy + u_map_st[0].zw).rgb +
           specular * texture(u_map_specular, uv * u_map_st[1].xy + u_map_st[1].zw).rgb;
}

float map_opacity(vec2 uv) {
    return texture(u_map_opacity, uv * u_map_st[2].xy + u_map_st[2].zw).r;
}
#endif
#ifdef PBR_TEXTURED
// A PBRMaterial's maps (glTF's packing; white where the material lacks one): the base colour
// (sRGB, decoded by the sampler) and its alpha, roughness in G and metallic in B (linear),
// occlusion in R (linear), the emissive colour (sRGB). pbr.glsl samples them where the
// scheme lights: at the pixel (Phong), the vertex (Gouraud), the polygon's centre (flat).
uniform sampler2D u_pbr_base_map;
uniform sampler2D u_pbr_mr_map;
uniform sampler2D u_pbr_occlusion_map;
uniform sampler2D u_pbr_emissive_map;
#ifdef PBR_NORMAL_MAP
uniform sampler2D u_pbr_normal_map;  // tangent space, linear: 2 x texel - 1

// The normal bent by the map at ``uv``: ``t`` the tangent frame (xyz towards increasing u,
// w the handedness: the bitangent is w n x t), ``n`` the unit normal, in one space.
vec3 pbr_mapped_normal(vec3 n, vec4 t, vec2 uv) {
    vec3 tangent = normalize(t.xyz - n * dot(n, t.xyz));
    vec3 bitangent = t.w * cross(n, tangent);
    vec3 m = texture(u_pbr_normal_map, uv).xyz * 2.0 - 1.0;
    return normalize(tangent * m.x + bitangent * m.y + n * m.z);
}
#endif

float pbr_map_alpha(vec2 uv) {
    return texture(u_pbr_base_map, uv).a;
}
#endif
#endif
