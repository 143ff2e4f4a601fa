// Shared by the BMFR kernels (seed 003, P2 §3): block geometry, the feature set and the layout
// of the per-block coefficient buffer. Defines from BMFRPass.cpp, each 0/1: BMFR_ALBEDO,
// BMFR_FP16_HISTORY, and the variant choices (docs/passes/BMFR.md "Variants"; "published" = the
// authors' OpenCL code, maZZZu/bmfr opencl/bmfr.cl): BMFR_PUBLISHED_SCALING, BMFR_MIRROR_EDGES,
// BMFR_FIT_MISSES, BMFR_CLAMP_BLOCKMAX, BMFR_UNROUNDED_COUNT.
#ifndef FOVEA_BMFR_COMMON_GLSL
#define FOVEA_BMFR_COMMON_GLSL

// P2 §6.1: 32x32 blocks; one workgroup of 256 threads per block, 4 pixels (rows) per thread.
#define BMFR_BLOCK 32
#define BMFR_BLOCK_PIXELS 1024
#define BMFR_THREADS 256
#define BMFR_ROWS_PER_THREAD 4

// P2 Eq. 8: T = [1, n.xyz, w.xyz, w.xyz^2] (M = 10), optionally followed by albedo.rgb.
#if BMFR_ALBEDO
#define BMFR_M 13
#else
#define BMFR_M 10
#endif
#define BMFR_COLS (BMFR_M + 3)  // augmented with z.rgb (P2 Eq. 4/7)

// Coefficient buffer, per block (floats): [0, 48) alpha[m * 3 + c]; [48, 51) position centre;
// [51, 54) position inverse half-range (0 = flat axis); [54, 57) z max per channel (clamp);
// [57] number of columns dropped as numerically dependent; [64, 80) feature offset m (fovea: the
// mid-range; published: the block minimum); [80, 96) feature scale m (fovea: inverse half-range,
// 0 = constant feature in this block; published: 1 / range, or 1 when the range is <= 1).
#define BMFR_COEF_STRIDE 96
#define BMFR_COEF_CENTER 48
#define BMFR_COEF_INVHALF 51
#define BMFR_COEF_ZMAX 54
#define BMFR_COEF_DROPPED 57
#define BMFR_COEF_FMID 64
#define BMFR_COEF_FINV 80

// Stats counters (uint[4], the `stats` output): see docs/passes/BMFR.md.
#define BMFR_STAT_NONFINITE_COLOR 0
#define BMFR_STAT_NONFINITE_GEOMETRY 1
#define BMFR_STAT_NEGATIVE_COLOR 2
#define BMFR_STAT_DROPPED_COLUMNS 3

// History colour storage (param fp16History): rgba16f or rgba32f. Stored values are clamped to
// the format's largest finite value, so a 1e6 firefly saturates instead of becoming +Inf.
#if BMFR_FP16_HISTORY
#define BMFR_HIST_FORMAT rgba16f
#define BMFR_HIST_MAX 65504.0
#else
#define BMFR_HIST_FORMAT rgba32f
#define BMFR_HIST_MAX 3.0e38
#endif

#ifdef BMFR_BLOCK_GRID_VP
#define VISUAL_POLAR_PARAMS
#include "common/visual_polar.glsl"
// This frame's block grid offset. On a Visual-Polar image whose warp draws P5 §3.3's staircase
// clip, the block columns follow the warp's x offset (the same P2 §6.1 sequence unless
// blockOffsets = false here), so every block column has one phi height by construction.
ivec2 bmfrBlockOffset(ivec2 pushed, int useVp) {
    if (useVp != 0 && vp.stair.x == uint(BMFR_BLOCK)) return ivec2(int(vp.stair.y), pushed.y);
    return pushed;
}
#endif

bool bmfrFinite3(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }
bool bmfrFinite4(vec4 v) { return !any(isnan(v)) && !any(isinf(v)); }

// Published edge handling (bmfr.cl `mirror`): a block row outside the image reads the pixel
// mirrored at the edge, so every block that touches the image fits 1024 rows. The clamp keeps an
// image narrower than a block (more than one size out) in bounds.
ivec2 bmfrMirror(ivec2 p, ivec2 size) {
    ivec2 m = ivec2(p.x < 0 ? -p.x - 1 : (p.x >= size.x ? 2 * size.x - p.x - 1 : p.x),
                    p.y < 0 ? -p.y - 1 : (p.y >= size.y ? 2 * size.y - p.y - 1 : p.y));
    return clamp(m, ivec2(0), size - 1);
}

// The unscaled features of one pixel (P2 Eq. 1/8); bmfrScale then maps each feature over the
// block (P2 §3.4). fovea scaling: positions are centred on the block's min/max mid-point and
// scaled to [-1, 1] BEFORE squaring: a scene 1e4 units from the origin gives the same features as
// one at the origin (squaring raw positions would lose everything but the constant part to float
// rounding), and every feature stays in [-1, 1] (fp16-safe). Published scaling (bmfr.cpp
// SCALED_FEATURE_BUFFERS): raw positions and their raw squares, scaled later; normals as they are.
void bmfrFeatures(vec3 w, vec3 n, vec3 albedo, vec3 center, vec3 invHalf,
                  out float f[BMFR_M]) {
#if BMFR_PUBLISHED_SCALING
    vec3 ws = w;
#else
    vec3 ws = clamp((w - center) * invHalf, -1.0, 1.0);  // invHalf = 0 for a flat axis
#endif
    f[0] = 1.0;
    f[1] = n.x;
    f[2] = n.y;
    f[3] = n.z;
    f[4] = ws.x;
    f[5] = ws.y;
    f[6] = ws.z;
    f[7] = ws.x * ws.x;
    f[8] = ws.y * ws.y;
    f[9] = ws.z * ws.z;
#if BMFR_ALBEDO
    f[10] = albedo.r;
    f[11] = albedo.g;
    f[12] = albedo.b;
#endif
}

// P2 §3.4: "T within every block is scaled to be in range [-1, 1]". fovea: offset = mid-range,
// inv = 1 / half-range (0 for a feature that is constant over the block: the constant column
// already represents it). Published (bmfr.cl `scale`): offset = block minimum, inv = 1 / range
// when the range exceeds 1, else 1, so a value lies in [0, 1] and the clamp never acts.
float bmfrScale(float f, float offset, float inv) { return clamp((f - offset) * inv, -1.0, 1.0); }

// Published regularization noise (bmfr.cl `random`, `add_random`): an integer hash of the row in
// the block, the feature column and the frame, the same pattern in every block, mapped to
// [-epsilon, epsilon). Every integer operation is unsigned 32-bit, as in OpenCL C.
float bmfrPublishedNoise(uint row, uint column, uint frame, float epsilon) {
    uint a = row + column * uint(BMFR_BLOCK_PIXELS) + frame * uint(BMFR_COLS * BMFR_BLOCK_PIXELS);
    a = (a + 0x7ed55d16u) + (a << 12);
    a = (a ^ 0xc761c23cu) ^ (a >> 19);
    a = (a + 0x165667b1u) + (a << 5);
    a = (a + 0xd3a2646cu) ^ (a << 9);
    a = (a + 0xfd7046c5u) + (a << 3);
    a = (a ^ 0xb55a4f09u) ^ (a >> 16);
    // float(UINT_MAX) rounds to 2^32, as convert_float does in the original.
    return epsilon * 2.0 * (float(a) / 4294967296.0 - 0.5);
}

#endif
