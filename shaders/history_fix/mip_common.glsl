// HistoryFix mip layout (seed 004: "mips 1..4"; specs §2 HistoryFix): level L holds, per eye,
// blocks of 2^L x 2^L pixels of that eye only, so no mip texel mixes the two eyes of a
// side-by-side image. Eye e's blocks start at column e * blocks (blocks = the per-eye block count
// of the widest eye at that level).
#ifndef FOVEA_HISTORY_FIX_MIP_GLSL
#define FOVEA_HISTORY_FIX_MIP_GLSL

#include "common/color.glsl"

int eyeOfPixel(int x, int eyeWidth, int eyes) { return min(x / eyeWidth, eyes - 1); }

// Optional demodulation (inputs `albedo`, `emission`; issue 13): a remodulated colour such as
// BMFR's `filtered` (= y * albedo' + emission, P2 §3.4) is averaged as y = (c - emission) /
// albedo' and the rebuilt y is multiplied back by the pixel's own albedo' and emission, so a
// coarse texel never mixes an emitter or a wall colour into a coplanar neighbour (the depth test
// cannot see those edges). albedo' = albedo > 1e-3 ? albedo : 1 per channel, NaN/Inf -> 1, as
// Remodulate and BMFR remodulate; a non-finite emission counts as 0.
vec3 hfSafeAlbedo(vec3 a, bool use) { return use ? demodulationAlbedo(a) : vec3(1.0); }
// Optional normal test (input `normal`, issue 13): a coarse texel holds the mean shading normal of
// its surface pixels, NOT renormalized; a pixel accepts it with weight
// saturate((n . n_L - cosT) / (1 - cosT)). n . n_L = |n_L| cos(angle), so a texel is refused when
// it points away from the pixel or when it mixes faces (|n_L| < 1: a block straddling a crease
// such as a box's top and front face, equal in depth at the edge but differently lit).
float hfNormalWeight(vec3 n, vec3 meanNormal, float cosT) {
    float d = dot(n, meanNormal);
    if (!(d > cosT)) return 0.0;                     // also NaN
    return min((d - cosT) / max(1.0 - cosT, 1e-6), 1.0);  // cosT < 1 (normalAngle >= 1 degree)
}
vec3 hfSafeEmission(vec3 e, bool use) {
    vec3 r = vec3(0.0);
    if (use)
        for (int c = 0; c < 3; ++c) r[c] = isnan(e[c]) || isinf(e[c]) ? 0.0 : e[c];
    return r;
}

#endif
