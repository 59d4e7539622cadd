// Linear [0, 1] to sRGB (IEC 61966-2-1), for programs that encode for display; the numpy
// twin is glshade.cpu.lighting's.
#ifndef SRGB_GLSL
#define SRGB_GLSL
vec3 encode_srgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}
#endif
