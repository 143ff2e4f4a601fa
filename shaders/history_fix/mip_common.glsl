// HistoryFix mip layout (seed 004: "mips 1..4"; specs §2 HistoryFix): level L holds, per eye,
// blocks of 2^L x 2^L pixels of that eye only, so no mip texel mixes the two eyes of a
// side-by-side image. Eye e's blocks start at column e * blocks (blocks = the per-eye block count
// of the widest eye at that level).
#ifndef FOVEA_HISTORY_FIX_MIP_GLSL
#define FOVEA_HISTORY_FIX_MIP_GLSL

int eyeOfPixel(int x, int eyeWidth, int eyes) { return min(x / eyeWidth, eyes - 1); }

#endif
