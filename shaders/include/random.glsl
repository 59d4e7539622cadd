// Random numbers: the PCG hash (O'Neill's RXS-M-XS output of one LCG step), to seed a
// stream from (seed, pixel, sample) so that a pixel's k-th sample never depends on how
// samples are grouped into passes, and the stream ``g_state`` it then runs.
#ifndef RANDOM_GLSL
#define RANDOM_GLSL
uint g_state;

uint pcg(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// the next number of the stream, uniform in [0, 1) with 24 bits
float rand() {
    g_state = g_state * 747796405u + 2891336453u;
    uint word = ((g_state >> ((g_state >> 28u) + 4u)) ^ g_state) * 277803737u;
    word = (word >> 22u) ^ word;
    return float(word >> 8u) * (1.0 / 16777216.0);
}

// the stream moved on by n (1, 2 or 3) numbers without drawing them: the LCG's steps
// composed (a^n s + c (a^(n-1) + ... + 1), mod 2^32), what a low-discrepancy draw that
// stands in for them costs the stream
void skip(uint n) {
    const uint A = 747796405u, C = 2891336453u;
    uint a = n == 1u ? A : n == 2u ? A * A : A * A * A;
    uint c = n == 1u ? C : n == 2u ? C * (A + 1u) : C * (A * A + A + 1u);
    g_state = g_state * a + c;
}

#ifdef LOW_DISCREPANCY
// Owen-scrambled Sobol points (Burley 2020, "Practical Hash-based Owen Scrambling"): each
// pair of dimensions a path uses is the first two Sobol dimensions, "padded" (each pair
// with its own seeds), the sample's index shuffled by an Owen scramble and each coordinate
// Owen-scrambled -- uniform in [0, 1)^2 for each sample (so unbiased), and the first 2^m
// samples of a pixel stratified over the pair's 2^m elementary intervals.
uint g_pixel_seed;  // the pixel's seed (set where its sample starts)

uint reverse_bits(uint x) {
    x = ((x >> 1u) & 0x55555555u) | ((x & 0x55555555u) << 1u);
    x = ((x >> 2u) & 0x33333333u) | ((x & 0x33333333u) << 2u);
    x = ((x >> 4u) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4u);
    x = ((x >> 8u) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8u);
    return (x >> 16u) | (x << 16u);
}

// Laine and Karras's nested uniform scramble of x's bits in reverse order (each bit
// flipped by a hash of the bits below it: every step carries only upwards), with
// Vegdahl's 2021 constants ("Building a Better LK Hash"), which scramble the low bits
// better than Burley's: on the Cornell box at 128² x 64 samples, 7.4% -> 7.1% RMS error,
// the pixels that see the light's edge 5.3% -> 4.8%
uint laine_karras(uint x, uint seed) {
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16u) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}

// the sample's point of dimension pair ``pair`` (sample k of this pixel)
vec2 sobol_pair(uint k, uint pair) {
    uint seed = pcg(g_pixel_seed ^ pcg(pair + 0x68bc21ebu));
    // the index Owen-scrambled: a shuffle within every aligned power-of-two block
    uint i = reverse_bits(laine_karras(reverse_bits(k), seed));
    // Sobol's second dimension (the Pascal matrix mod 2) as a zeta transform over the bit
    // positions, left reversed: Owen scrambling reverses it back
    uint y = i;
    y ^= (y >> 1u) & 0x55555555u;
    y ^= (y >> 2u) & 0x33333333u;
    y ^= (y >> 4u) & 0x0F0F0F0Fu;
    y ^= (y >> 8u) & 0x00FF00FFu;
    y ^= (y >> 16u) & 0x0000FFFFu;
    // the first dimension is reverse_bits(i): reversed, it is i itself
    uint a = reverse_bits(laine_karras(i, pcg(seed + 1u)));
    uint b = reverse_bits(laine_karras(y, pcg(seed + 2u)));
    return vec2(float(a >> 8u), float(b >> 8u)) * (1.0 / 16777216.0);
}
#endif
#endif
