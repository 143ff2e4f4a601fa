// Seeded, stateless random numbers: every value is a hash of (pixel, frame, sample, bounce, seed),
// so a run is reproducible bit for bit on the same driver (ARCHITECTURE "Rendering model").
#ifndef FOVEA_RANDOM_GLSL
#define FOVEA_RANDOM_GLSL

// PCG-style integer hash (Jarzynski & Olano 2020, "Hash Functions for GPU Rendering").
uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

uint hashCombine(uint seed, uint v) { return pcgHash(seed ^ (v + 0x9e3779b9u + (seed << 6) + (seed >> 2))); }

// Uniform float in [0, 1): 24 mantissa bits, so 1.0 is never returned.
float uintToUnitFloat(uint v) { return float(v >> 8) * (1.0 / 16777216.0); }

#endif
