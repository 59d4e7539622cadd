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
#endif
