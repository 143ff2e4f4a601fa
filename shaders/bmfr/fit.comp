#version 460
// BMFR phase II, fit (seed 003, P2 §3.3-3.4, §6.1): one workgroup per 32x32 block (shifted by
// this frame's block offset). Builds the features (P2 Eq. 8), scales positions per block to
// [-1, 1], adds zero-mean uniform noise in [-eps, eps] to the features for the fit only
// (stochastic regularization, Eq. 7), runs an augmented Householder QR on [T + N, z.rgb] that
// only computes R (Eq. 4/5) and solves R alpha = r by back substitution. The rows live in
// registers (4 per thread); column sums go through one shared-memory tree reduction.
//
// The variant defines (bmfr_common.glsl) select the published code's scaling, noise, edge rows and
// miss rows; the QR below is the same for both.
//
// Guards the published code does not have: sign-aware reflections (no cancellation); a column
// whose remaining norm is zero or below `dropTolerance` x its original norm is dropped (alpha =
// 0, the rows stay for later columns) instead of dividing by a zero pivot, so rank-deficient
// blocks fit the span of the remaining columns (block mean at worst); z is scaled by its block
// maximum so every matrix entry is O(1) (fp16-safe).
#extension GL_GOOGLE_include_directive : require
#define BMFR_BLOCK_GRID_VP
#include "bmfr/bmfr_common.glsl"
#include "common/random.glsl"

layout(local_size_x = 256) in;

uniform sampler2D accumulated;  // phase I output: z.rgb (finite, >= 0)
uniform sampler2D position;
uniform sampler2D normal;
#if BMFR_ALBEDO
uniform sampler2D albedo;  // a feature only with features = albedo
#endif
layout(std430) buffer Coefficients { float v[]; } coefficients;
layout(std430) buffer Stats { uint counters[4]; } stats;

layout(push_constant) uniform Params {
    ivec2 size;
    ivec2 offset;  // this frame's block offset (P2 §3.5)
    int blocksX;
    uint seed;      // run seed mixed with the frame index
    float epsilon;  // stochastic regularization amplitude (P2 §3.4: 0.01)
    float dropTolerance;
    int useVp;  // 1: the `vp` block may move the block columns (bmfrBlockOffset)
    uint frame;  // frame index: the published noise pattern's frame term
} pc;

const float kBig = 3.0e38;

shared float sRed[BMFR_COLS][BMFR_THREADS];
shared float sRow[BMFR_COLS];   // the pivot row of the current step (R row in the making)
shared float sScale[BMFR_COLS]; // per-step factors broadcast by thread 0
shared float sNorm0[BMFR_COLS]; // original column norms
shared int sRowOf[BMFR_M];      // R row of each column, -1 = dropped
shared float sR[BMFR_M][BMFR_COLS];
shared int sRank;
shared int sAccept;

// Reduction of sRed over the 256 threads for columns [first, end); op 0 = sum, 1 = min. Four
// values per step (256 -> 64 -> 16 -> 4 -> 1): 4 barriers instead of 8 (P2 §6.1, Table 1: more
// levels per synchronization). Thread t < s reads t + s, t + 2s, t + 3s, which no thread writes
// in that step.
void reduce(int first, int end, int op) {
    uint t = gl_LocalInvocationID.x;
    barrier();
    for (uint s = BMFR_THREADS / 4; s > 0u; s >>= 2) {
        if (t < s)
            for (int c = first; c < end; ++c) {
                float a = sRed[c][t], b = sRed[c][t + s], d = sRed[c][t + 2u * s],
                      e = sRed[c][t + 3u * s];
                sRed[c][t] = op == 0 ? (a + b) + (d + e) : min(min(a, b), min(d, e));
            }
        barrier();
    }
}

void main() {
    uint t = gl_LocalInvocationID.x;
    int block = int(gl_WorkGroupID.x);
    ivec2 origin = ivec2(block % pc.blocksX, block / pc.blocksX) * BMFR_BLOCK -
                   bmfrBlockOffset(pc.offset, pc.useVp);

    float A[BMFR_ROWS_PER_THREAD][BMFR_COLS];
    bool valid[BMFR_ROWS_PER_THREAD];
    vec3 wv[BMFR_ROWS_PER_THREAD], nv[BMFR_ROWS_PER_THREAD], av[BMFR_ROWS_PER_THREAD],
        zv[BMFR_ROWS_PER_THREAD];

    // Load; rows outside the image or without (finite) geometry are zero rows: they do not
    // change the least-squares solution. Published edges: a block that touches the image fills
    // its outside rows with mirrored pixels. Published misses: a miss is a row with the
    // G-buffer's miss features (zeros) and its accumulated colour.
#if BMFR_MIRROR_EDGES
    bool touches = all(lessThan(origin, pc.size)) && all(greaterThan(origin + BMFR_BLOCK, ivec2(0)));
#endif
    for (int j = 0; j < BMFR_ROWS_PER_THREAD; ++j) {
        int row = int(t) + j * BMFR_THREADS;
        ivec2 p = origin + ivec2(row % BMFR_BLOCK, row / BMFR_BLOCK);
        valid[j] = false;
        wv[j] = nv[j] = av[j] = zv[j] = vec3(0.0);
        bool inside = all(greaterThanEqual(p, ivec2(0))) && all(lessThan(p, pc.size));
#if BMFR_MIRROR_EDGES
        if (!inside && touches) {
            p = bmfrMirror(p, pc.size);
            inside = true;
        }
#endif
        if (!inside) continue;
        vec4 w = texelFetch(position, p, 0);
        vec3 n = texelFetch(normal, p, 0).xyz;
        vec3 z = texelFetch(accumulated, p, 0).rgb;
        vec3 a = vec3(0.0);
#if BMFR_ALBEDO
        a = texelFetch(albedo, p, 0).rgb;
        if (!bmfrFinite3(a)) a = vec3(0.0);
        a = clamp(a, 0.0, 1.0);
#endif
        if (!bmfrFinite3(w.xyz) || !bmfrFinite3(n) || !bmfrFinite3(z)) continue;
#if !BMFR_FIT_MISSES
        if (!(w.w > 0.0)) continue;
#endif
        valid[j] = true;
        wv[j] = w.xyz;
        nv[j] = clamp(n, -1.0, 1.0);
        av[j] = a;
        zv[j] = max(z, vec3(0.0));
    }

    // Per-block min/max of positions and max of z, as one min-reduction over 9 columns.
    for (int c = 0; c < 9; ++c) {
        float m = kBig;
        for (int j = 0; j < BMFR_ROWS_PER_THREAD; ++j) {
            if (!valid[j]) continue;
            float v = c < 3 ? wv[j][c] : (c < 6 ? -wv[j][c - 3] : -zv[j][c - 6]);
            m = min(m, v);
        }
        sRed[c][t] = m;
    }
    reduce(0, 9, 1);
    vec3 wMin = vec3(sRed[0][0], sRed[1][0], sRed[2][0]);
    vec3 wMax = -vec3(sRed[3][0], sRed[4][0], sRed[5][0]);
    vec3 zMax = -vec3(sRed[6][0], sRed[7][0], sRed[8][0]);
    barrier();  // everyone has read the result before sRed is written again
    bool empty = wMin.x >= kBig;  // no valid pixel in the block
    vec3 center = empty ? vec3(0.0) : 0.5 * wMin + 0.5 * wMax;  // halves first: no overflow
    vec3 halfRange = empty ? vec3(0.0) : 0.5 * wMax - 0.5 * wMin;
    vec3 invHalf;
    for (int c = 0; c < 3; ++c) {
        // An axis whose extent is at float-rounding level of its magnitude is flat: scaling it
        // to [-1, 1] would turn rounding noise into a full-range feature.
        float mag = max(abs(wMin[c]), abs(wMax[c]));
        float flatExtent = max(1e-6, 2e-6 * mag);
        invHalf[c] = halfRange[c] > flatExtent ? 1.0 / halfRange[c] : 0.0;
    }
    vec3 zScale;
    for (int c = 0; c < 3; ++c) zScale[c] = zMax[c] > 1e-30 && !empty ? zMax[c] : 1.0;

    // A block without one valid pixel has nothing to fit: the extra row/column of blocks that
    // the offsets push off the image, and on a Visual-Polar image the blocks that are all clipped
    // or off-screen (13-16 of 49 at 256x256, a third of the fit's work). weighted_sum reads a
    // block only for a valid pixel, so it never reads these; they get zeros and skip the QR.
    // `empty` comes from shared memory: the whole workgroup returns together.
    if (empty) {
        if (t == 0u)
            for (int k = 0; k < BMFR_COEF_STRIDE; ++k)
                coefficients.v[block * BMFR_COEF_STRIDE + k] = 0.0;
        return;
    }

    // Unscaled features, then their per-block min/max (two min-reductions over columns 1..M-1).
    for (int j = 0; j < BMFR_ROWS_PER_THREAD; ++j) {
        float f[BMFR_M];
        bmfrFeatures(wv[j], nv[j], av[j], center, invHalf, f);
        for (int m = 0; m < BMFR_M; ++m) A[j][m] = f[m];
    }
    float fMin[BMFR_M], fMax[BMFR_M];
    for (int pass = 0; pass < 2; ++pass) {
        float sign = pass == 0 ? 1.0 : -1.0;
        for (int m = 1; m < BMFR_M; ++m) {
            float v = kBig;
            for (int j = 0; j < BMFR_ROWS_PER_THREAD; ++j)
                if (valid[j]) v = min(v, sign * A[j][m]);
            sRed[m][t] = v;
        }
        reduce(1, BMFR_M, 1);
        for (int m = 1; m < BMFR_M; ++m) {
            if (pass == 0) fMin[m] = sRed[m][0];
            else fMax[m] = -sRed[m][0];
        }
        barrier();  // everyone has read the result before sRed is written again
    }
    float fMid[BMFR_M], fInv[BMFR_M];
    fMid[0] = 0.0;
    fInv[0] = 1.0;
    for (int m = 1; m < BMFR_M; ++m) {
#if BMFR_PUBLISHED_SCALING
        // bmfr.cpp: only the positions and their squares (columns 4-9) are scaled, by the block
        // range when it exceeds 1 scene unit, else only shifted to start at 0 (so the scaling
        // depends on the scene's units); normals (and albedo, fovea's extension) stay as they are.
        bool scaled = m >= 4 && m <= 9;
        float range = fMax[m] - fMin[m];  // both finite: the block has a valid row
        fMid[m] = scaled ? fMin[m] : 0.0;
        fInv[m] = scaled && range > 1.0 ? 1.0 / range : 1.0;
#else
        // Every unscaled feature is O(1) (unit normals, positions already in [-1, 1], albedo in
        // [0, 1]); a half-range at fp16 rounding level (normals, albedo come as fp16) is noise.
        float h = 0.5 * fMax[m] - 0.5 * fMin[m];
        fMid[m] = empty ? 0.0 : 0.5 * fMax[m] + 0.5 * fMin[m];
        fInv[m] = !empty && h > 1e-3 ? 1.0 / h : 0.0;
#endif
    }

    // Rows of [T + N, z / zScale].
    for (int j = 0; j < BMFR_ROWS_PER_THREAD; ++j) {
        int row = int(t) + j * BMFR_THREADS;
#if !BMFR_PUBLISHED_SCALING
        uint h = hashCombine(hashCombine(pc.seed, uint(block)), uint(row));
#endif
        for (int m = 0; m < BMFR_M; ++m) {
#if BMFR_PUBLISHED_SCALING
            // bmfr.cl add_random: no noise on the constant column.
            float noise = m == 0 ? 0.0 : bmfrPublishedNoise(uint(row), uint(m), pc.frame, pc.epsilon);
#else
            h = pcgHash(h);
            float noise = (2.0 * uintToUnitFloat(h) - 1.0) * pc.epsilon;  // zero-mean uniform
#endif
            float f = m == 0 ? 1.0 : bmfrScale(A[j][m], fMid[m], fInv[m]);
            A[j][m] = valid[j] ? f + noise : 0.0;
        }
        for (int c = 0; c < 3; ++c) A[j][BMFR_M + c] = valid[j] ? zv[j][c] / zScale[c] : 0.0;
    }

    // Original column norms (reference for the drop test).
    for (int c = 0; c < BMFR_COLS; ++c) {
        float s = 0.0;
        for (int j = 0; j < BMFR_ROWS_PER_THREAD; ++j) s += A[j][c] * A[j][c];
        sRed[c][t] = s;
    }
    reduce(0, BMFR_COLS, 0);
    if (t == 0u) {
        for (int c = 0; c < BMFR_COLS; ++c) sNorm0[c] = sqrt(sRed[c][0]);  // sum of squares >= 0
        sRank = 0;
    }
    barrier();

    // Augmented Householder QR, computing only R (P2 §3.4). Column k reflects rows >= r, where r
    // counts the columns accepted so far.
    for (int k = 0; k < BMFR_M; ++k) {
        int r = sRank;  // uniform: written by thread 0 before the last barrier
        // Broadcast the pivot row r (owned by thread r % 256, slot r / 256).
        if (int(t) == r % BMFR_THREADS)
            for (int c = k; c < BMFR_COLS; ++c) sRow[c] = A[r / BMFR_THREADS][c];
        // Dot products of column k with columns k.. over rows >= r.
        for (int c = k; c < BMFR_COLS; ++c) {
            float s = 0.0;
            for (int j = 0; j < BMFR_ROWS_PER_THREAD; ++j) {
                int row = int(t) + j * BMFR_THREADS;
                if (row >= r) s += A[j][k] * A[j][c];
            }
            sRed[c][t] = s;
        }
        reduce(k, BMFR_COLS, 0);
        if (t == 0u) {
            float norm = sqrt(max(sRed[k][0], 0.0));
            bool accept = norm > 1e-30 && norm > pc.dropTolerance * sNorm0[k];
            sAccept = accept ? 1 : 0;
            if (accept) {
                float xr = sRow[k];
                // Sign-aware: alpha has the opposite sign of x_r, so v_r = x_r - alpha never
                // cancels; v.v = 2 |x| (|x| + |x_r|) >= 2 norm^2 > 0.
                float alpha = xr >= 0.0 ? -norm : norm;
                float vv = 2.0 * norm * (norm + abs(xr));
                sScale[k] = alpha;
                for (int c = k + 1; c < BMFR_COLS; ++c) {
                    float vA = sRed[c][0] - alpha * sRow[c];  // v.A_c = x.A_c - alpha A[r][c]
                    sScale[c] = 2.0 * vA / vv;
                }
                sRowOf[k] = r;
                sRank = r + 1;
            } else {
                sRowOf[k] = -1;  // dropped: alpha_k = 0 (its rows stay for later columns)
            }
        }
        barrier();
        if (sAccept == 0) continue;
        float alpha = sScale[k];
        for (int j = 0; j < BMFR_ROWS_PER_THREAD; ++j) {
            int row = int(t) + j * BMFR_THREADS;
            if (row < r) continue;
            float v = row == r ? A[j][k] - alpha : A[j][k];
            for (int c = k + 1; c < BMFR_COLS; ++c) A[j][c] -= sScale[c] * v;
            A[j][k] = row == r ? alpha : 0.0;
        }
        barrier();  // sRow / sScale are rewritten by the next step
    }

    // R rows to shared memory, then back substitution (R alpha = r, Eq. 5) by one thread.
    int rank = sRank;
    for (int j = 0; j < BMFR_ROWS_PER_THREAD; ++j) {
        int row = int(t) + j * BMFR_THREADS;
        if (row < rank)
            for (int c = 0; c < BMFR_COLS; ++c) sR[row][c] = A[j][c];
    }
    barrier();
    if (t == 0u) {
        int base = block * BMFR_COEF_STRIDE;
        float alpha[BMFR_M][3];
        int dropped = 0;
        for (int k = BMFR_M - 1; k >= 0; --k) {
            int r = sRowOf[k];
            for (int c = 0; c < 3; ++c) {
                if (r < 0) { alpha[k][c] = 0.0; continue; }
                float s = sR[r][BMFR_M + c];
                for (int m = k + 1; m < BMFR_M; ++m) s -= sR[r][m] * alpha[m][c];
                // |R[r][k]| = the accepted norm > 0 (test above).
                alpha[k][c] = s / sR[r][k];
            }
            if (r < 0) ++dropped;
        }
        bool finite = true;
        for (int k = 0; k < BMFR_M; ++k)
            finite = finite && bmfrFinite3(vec3(alpha[k][0], alpha[k][1], alpha[k][2]));
        for (int k = 0; k < BMFR_M; ++k)
            for (int c = 0; c < 3; ++c)
                coefficients.v[base + k * 3 + c] = finite ? alpha[k][c] * zScale[c] : 0.0;
        for (int c = 0; c < 3; ++c) {
            coefficients.v[base + BMFR_COEF_CENTER + c] = center[c];
            coefficients.v[base + BMFR_COEF_INVHALF + c] = invHalf[c];
            coefficients.v[base + BMFR_COEF_ZMAX + c] = empty ? 0.0 : zMax[c];
        }
        coefficients.v[base + BMFR_COEF_DROPPED] = float(finite ? dropped : -1);
        for (int m = 0; m < BMFR_M; ++m) {
            coefficients.v[base + BMFR_COEF_FMID + m] = fMid[m];
            coefficients.v[base + BMFR_COEF_FINV + m] = fInv[m];
        }
        // Empty blocks (outside the image) drop every column by construction: not counted.
        if (!empty && (dropped > 0 || !finite))
            atomicAdd(stats.counters[BMFR_STAT_DROPPED_COLUMNS], 1u);
    }
}
