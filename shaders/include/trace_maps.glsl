// The path tracer's texture maps (MAPS defined; pathtrace/pack.py map_tables): a hit's
// texture coordinates across its triangle and its material's colour map (the notes'
// diffuse map, glTF's base colour), glTF's metallic-roughness and emissive maps read there,
// bilinear
// between the four nearest texels (colours decoded to linear before: as GL's sRGB
// textures filter; a mipmapped texture's first level) or the nearest texel, wrapped or
// clamped, as the texture says.
#ifndef TRACE_MAPS_GLSL
#define TRACE_MAPS_GLSL
uniform int u_uvs;     // corner (u, v), 3 texels a triangle
uniform int u_maps;    // a material's five slots, 2 texels each
uniform int u_tangents;  // a texel a triangle: dP/du (world), the handedness
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

// the texture coordinates at triangle k's point ``bary``
vec2 map_uv(int k, vec2 bary) {
    return (1.0 - bary.x - bary.y) * fetch(u_uvs + 3 * k).xy +
           bary.x * fetch(u_uvs + 3 * k + 1).xy + bary.y * fetch(u_uvs + 3 * k + 2).xy;
}

// material m's map in ``slot`` (0 colour, 1 metallic-roughness, 2 emissive, 3 normal, 4
// opacity: its alpha) at triangle k's point ``bary``; ``none`` where it has no map there
vec4 map_slot(int m, int k, int slot, vec2 bary, vec4 none) {
    vec4 s0 = fetch(u_maps + 10 * m + 2 * slot), s1 = fetch(u_maps + 10 * m + 2 * slot + 1);
    return s0.x >= 0.0 ? map_sample(int(s0.x), s0.y, s1, map_uv(k, bary)) : none;
}

// material m's colour and metallic-roughness maps at triangle k's point, applied to
// ``bsdf`` (glTF's packing: roughness in green, metallic in blue)
void apply_maps(inout Bsdf bsdf, int m, int k, vec2 bary) {
    bsdf.rho *= map_slot(m, k, 0, bary, vec4(1.0)).rgb;
    vec4 mr = map_slot(m, k, 1, bary, vec4(1.0));
    bsdf.roughness *= mr.g;
    bsdf.metallic *= mr.b;
}
#endif
