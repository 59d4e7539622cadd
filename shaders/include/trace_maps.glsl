// The path tracer's texture maps (MAPS defined; pathtrace/pack.py map_tables): a hit's
// texture coordinates across its triangle and its material's colour map (the notes'
// diffuse map, glTF's base colour) and glTF's metallic-roughness map read there, bilinear
// between the four nearest texels (colours decoded to linear before: as GL's sRGB
// textures filter; a mipmapped texture's first level) or the nearest texel, wrapped or
// clamped, as the texture says.
#ifndef TRACE_MAPS_GLSL
#define TRACE_MAPS_GLSL
uniform int u_uvs;     // corner (u, v), 3 texels a triangle
uniform int u_maps;    // a material's two slots, 2 texels each
uniform int u_texdir;  // a texel a texture: (first texel from here, width, height, -)

ivec2 map_wrap(ivec2 i, ivec2 size, bool clamp_) {
    return clamp_ ? clamp(i, ivec2(0), size - 1) : ((i % size) + size) % size;
}

// texture ``t`` at (u, v) = uv x scale + offset (``so``), bilinear -- or, ``how`` >= 2,
// the nearest texel (``how`` odd: clamped, else repeated)
vec4 map_sample(int t, float how, vec4 so, vec2 uv) {
    vec4 dir = fetch(u_texdir + t);
    int first = u_texdir + floatBitsToInt(dir.x);
    ivec2 size = ivec2(dir.yz);
    bool clamp_ = mod(how, 2.0) > 0.5;
    vec2 q = (uv * so.xy + so.zw) * vec2(size);
    if (how > 1.5) {
        ivec2 i = map_wrap(ivec2(floor(q)), size, clamp_);
        return fetch(first + i.y * size.x + i.x);
    }
    vec2 p = q - 0.5;
    vec2 f = p - floor(p);
    ivec2 i0 = ivec2(floor(p));
    ivec2 a = map_wrap(i0, size, clamp_), b = map_wrap(i0 + 1, size, clamp_);
    vec4 t00 = fetch(first + a.y * size.x + a.x), t10 = fetch(first + a.y * size.x + b.x);
    vec4 t01 = fetch(first + b.y * size.x + a.x), t11 = fetch(first + b.y * size.x + b.x);
    return mix(mix(t00, t10, f.x), mix(t01, t11, f.x), f.y);
}

// material m's maps at triangle k's point (barycentrics ``bary``), applied to ``bsdf``
void apply_maps(inout Bsdf bsdf, int m, int k, vec2 bary) {
    vec2 uv = (1.0 - bary.x - bary.y) * fetch(u_uvs + 3 * k).xy +
              bary.x * fetch(u_uvs + 3 * k + 1).xy + bary.y * fetch(u_uvs + 3 * k + 2).xy;
    vec4 c0 = fetch(u_maps + 4 * m), c1 = fetch(u_maps + 4 * m + 1);
    if (c0.x >= 0.0) bsdf.rho *= map_sample(int(c0.x), c0.y, c1, uv).rgb;
    vec4 r0 = fetch(u_maps + 4 * m + 2), r1 = fetch(u_maps + 4 * m + 3);
    if (r0.x >= 0.0) {  // (glTF's packing: roughness in green, metallic in blue)
        vec4 mr = map_sample(int(r0.x), r0.y, r1, uv);
        bsdf.roughness *= mr.g;
        bsdf.metallic *= mr.b;
    }
}
#endif
