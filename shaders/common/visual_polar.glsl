// The Visual-Polar mapping of seed 003 P5 §3.2 (thesis §4.6.2), shared by every pass that reads
// or writes Visual-Polar images. Twin of core/sampling/VisualPolar.{h,cpp} (conventions there and
// in docs/visual-polar.md); the tests compare the two.
//
// Per eye: column i <-> rho = (i + 0.5) / W, row j <-> t = phi / 2 pi = (j + 0.5) / n(i); n(i) =
// H outside the fovea, ceil(H rho / rho_f) inside (P5's triangular clip). Screen radius r =
// dMax e(rho) / 80, e linear in the fovea and the inverse acuity CDF (Eq. 2) beyond.
//
// Define VISUAL_POLAR_PARAMS (readonly) or VISUAL_POLAR_PARAMS_WRITE before including to get the
// `vp` block written by the VisualPolarWarp pass (field `vp`, 80 bytes, std430).
#ifndef FOVEA_VISUAL_POLAR_GLSL
#define FOVEA_VISUAL_POLAR_GLSL

const float kVpPi = 3.14159265358979;
const float kVpFlatDegrees = 5.79;
const float kVpMaxDegrees = 80.0;

struct VisualPolarMap {
    vec2 screen;         // eye image size (pixels), >= 1
    vec2 gaze;           // pixels of the eye image, on the screen
    float dMax;          // largest gaze-to-corner distance, >= 0.5
    uint width;          // VP texels per eye, >= 1
    uint height;         // >= 1
    float foveaFraction; // rho_f in (0, 1]
    float foveaDegrees;  // e_f = f^-1(rho_f)
    // P5 §3.3's staircase clip: 0 = the triangular clip; B > 0 = every column takes the height of
    // the last column of its B-column block (BMFR's block columns, shifted by the frame's block
    // offset), so a block column has one phi height. Phases are (offset x + eye W) mod B.
    uint stairBlock;
    uint stairPhase;      // this frame's
    uint stairPrevPhase;  // the previous frame's (history images were traced with it)
};

// P5 Eq. 2 normalized by its value at 80 degrees (1091.31); pi e^2 where the acuity is flat.
float vpAcuityCdf(float e) {
    e = clamp(e, 0.0, kVpMaxDegrees);
    if (e <= kVpFlatDegrees) return kVpPi * e * e / 1091.3132;
    float a = 0.3 * e + 1.0;  // >= 1
    return ((1.0 / a + log(a)) * 166.4 * kVpPi - 612.3) / 1091.3132;
}

// df/de = 2 pi e m(e) / h(80): positive for e > 0.
float vpAcuityCdfDerivative(float e) {
    e = clamp(e, 0.0, kVpMaxDegrees);
    float a = 0.3 * e + 1.0;
    float raw = e <= kVpFlatDegrees ? 2.0 * kVpPi * e : 166.4 * kVpPi * 0.09 * e / (a * a);
    return raw / 1091.3132;
}

// P5 Eq. 3 (= P4 Eq. 7's polynomial branch): the published least-squares fit of f^-1 for u
// beyond f(5.79) = 0.0965.
float vpAcuityInversePolynomial(float u) {
    return (((25.09 * u + 0.1680) * u + 27.61) * u + 23.87) * u + 3.232;
}

// f^-1(u): closed form where the acuity is flat, else P5 Eq. 3 (the fitted polynomial) refined
// by Newton steps on Eq. 2 (Eq. 3 alone is up to 0.03 degrees and, in density, 2.4 % off).
float vpAcuityInverse(float u) {
    u = clamp(u, 0.0, 1.0);
    if (u <= 0.0965067) return sqrt(u * 1091.3132 / kVpPi);
    float e = vpAcuityInversePolynomial(u);
    e = clamp(e, kVpFlatDegrees, kVpMaxDegrees);
    for (int k = 0; k < 3; ++k)  // derivative >= 0.0042 on [5.79, 80]: no division by ~0
        e = clamp(e - (vpAcuityCdf(e) - u) / vpAcuityCdfDerivative(e), kVpFlatDegrees,
                  kVpMaxDegrees);
    return e;
}

// How far (relative) above an integer H rho / rho_f may come out and still count as that integer
// in vpRows (VisualPolar.h kVisualPolarRowsSlack, the C++ twin's). The value is often an exact
// integer (W = H and rho_f = 0.1 make it one in every fovea column); float rounding lifted some by
// an ulp and the ceil then by a whole row the double twin did not have (column 4 of 70x70: 46
// rows here, 45 there), so Unwarp read a 46-row column that held 45. Float is at most ~6 ulps
// (7e-7) off with Vulkan's 2.5-ulp division; 2e-6 is ~3x that.
const float kVpRowsSlack = 2e-6;

// n(i): the phi height of column i, in [1, H]. With the staircase, the height of the last column
// of i's block column (the largest of the block: the fovea keeps at least its density).
uint vpRows(VisualPolarMap m, uint column) {
    if (m.stairBlock > 0u)
        column = min(column + (m.stairBlock - 1u) - (column + m.stairPhase) % m.stairBlock,
                     m.width - 1u);
    float rho = (float(column) + 0.5) / float(m.width);
    if (rho >= m.foveaFraction) return m.height;
    float n = float(m.height) * rho / m.foveaFraction;  // foveaFraction >= 0.1
    return clamp(uint(ceil(n * (1.0 - kVpRowsSlack))), 1u, m.height);
}

float vpEccentricity(VisualPolarMap m, float rho) {
    if (rho < m.foveaFraction) return max(rho, 0.0) * m.foveaDegrees / m.foveaFraction;
    return vpAcuityInverse(rho);
}

float vpRhoOfEccentricity(VisualPolarMap m, float e) {
    if (e < m.foveaDegrees) return max(e, 0.0) * m.foveaFraction / m.foveaDegrees;
    return vpAcuityCdf(e);
}

float vpRadius(VisualPolarMap m, float rho) { return m.dMax * vpEccentricity(m, rho) / kVpMaxDegrees; }

// The same grid around another gaze (pixels of the eye image, clamped onto it; P5 §3.2: rho = 1
// reaches the farthest corner, so dMax follows the gaze). GBuffer maps the previous screen
// position with the previous frame's gaze (P5 §3.3) so a gaze move reprojects like a camera move.
VisualPolarMap vpWithGaze(VisualPolarMap m, vec2 gaze) {
    m.gaze = clamp(gaze, vec2(0.0), m.screen);
    vec2 d = max(m.gaze, m.screen - m.gaze);
    m.dMax = max(length(d), 0.5);
    return m;
}

// VP (rho, t = phi / 2 pi) -> screen pixels of the eye image.
vec2 vpToScreen(VisualPolarMap m, float rho, float t) {
    float r = vpRadius(m, rho), phi = 2.0 * kVpPi * t;
    return m.gaze + r * vec2(cos(phi), sin(phi));
}

// Screen pixels -> (rho, t), t in [0, 1). The gaze maps to (0, 0): no NaN at rho = 0.
vec2 vpToVisualPolar(VisualPolarMap m, vec2 p) {
    vec2 d = p - m.gaze;
    float r = length(d);
    float t = r > 0.0 ? atan(d.y, d.x) / (2.0 * kVpPi) : 0.0;
    t = fract(t + 1.0);  // [-0.5, 0.5] -> [0, 1)
    return vec2(vpRhoOfEccentricity(m, r * kVpMaxDegrees / m.dMax), t);  // dMax >= 0.5
}

// The staircase phase of eye `eye`: its columns start at eye W in the side-by-side image, whose
// block grid is shifted by `offset` (P2 §6.1). block 0 = no staircase.
uint vpStairPhaseOf(uint block, uint offset, uint eye, uint width) {
    return block == 0u ? 0u : (offset + eye * width) % block;
}

// The same map with the previous frame's phi heights: history images were traced with them (the
// staircase moves with the block offsets every frame). Positions (rho, t) do not change.
VisualPolarMap vpPrevious(VisualPolarMap m) {
    m.stairPhase = m.stairPrevPhase;
    return m;
}

// Screen position of texel (i, j)'s centre plus a jitter in VP texels (thesis §4.6.2: jitter
// in VP space keeps TAA working).
vec2 vpTexelToScreen(VisualPolarMap m, uvec2 texel, vec2 jitter) {
    float rho = (float(texel.x) + 0.5 + jitter.x) / float(m.width);
    float t = (float(texel.y) + 0.5 + jitter.y) / float(vpRows(m, texel.x));
    return vpToScreen(m, rho, t);
}

// Neighbour addressing (P5 §3.3): clamp on rho, wrap on phi at the target column's own height.
ivec2 vpNeighbour(VisualPolarMap m, ivec2 texel, ivec2 step) {
    int i0 = clamp(texel.x, 0, int(m.width) - 1);
    int i1 = clamp(i0 + step.x, 0, int(m.width) - 1);
    float n0 = float(vpRows(m, uint(i0))), n1 = float(vpRows(m, uint(i1)));
    float t = (float(texel.y + step.y) + 0.5) / n0;
    return ivec2(i1, clamp(int(floor(fract(t) * n1)), 0, int(n1) - 1));
}

// The continuous previous position of texel `texel` (eye-local column, row) moved by a GBuffer
// Visual-Polar motion vector (columns, rows of the texel's own column): x in columns (texel
// centres at +0.5), y = t = phi / 2 pi (any real: wrapped by vpBilinearTaps).
vec2 vpMovedPosition(VisualPolarMap m, ivec2 texel, vec2 motion) {
    uint column = uint(clamp(texel.x, 0, int(m.width) - 1));
    float n = float(vpRows(m, column));  // >= 1
    return vec2(float(texel.x) + 0.5 + motion.x, (float(texel.y) + 0.5 + motion.y) / n);
}

// P5 §3.3/§3.4: the 4 bilinear taps of a continuous VP position (x in eye-local columns, t =
// phi / 2 pi) in temporal reprojection. Tap k = (k & 1, k >> 1): column c0 + (k & 1), and in
// that column the row r0 + (k >> 1) at the column's OWN height n(c) (a row index means a
// different phi in columns of different heights: the fovea's triangular clip), wrapped on phi
// (no seam at phi = 0). Columns are clamped on rho. Texels are eye-local; weights sum to 1.
void vpBilinearTaps(VisualPolarMap m, vec2 position, out ivec2 taps[4], out float weights[4]) {
    float x = position.x - 0.5;
    float c0f = floor(x);
    float fx = clamp(x - c0f, 0.0, 1.0);
    for (int side = 0; side < 2; ++side) {
        int c = clamp(int(c0f) + side, 0, int(m.width) - 1);
        int n = int(vpRows(m, uint(c)));  // >= 1
        float y = fract(position.y) * float(n) - 0.5;
        float r0f = floor(y);
        float fy = clamp(y - r0f, 0.0, 1.0);
        int r0 = (int(r0f) % n + n) % n;  // r0f >= -1
        float wx = side == 1 ? fx : 1.0 - fx;
        taps[side] = ivec2(c, r0);
        taps[side + 2] = ivec2(c, (r0 + 1) % n);
        weights[side] = wx * (1.0 - fy);
        weights[side + 2] = wx * fy;
    }
}

// Rows of column `column` at phi-mip level `level`: ceil(n / 2^level), >= 1.
uint vpRowsAtLevel(VisualPolarMap m, uint column, uint level) {
    return (vpRows(m, column) + (1u << level) - 1u) >> level;
}

#if defined(VISUAL_POLAR_PARAMS) || defined(VISUAL_POLAR_PARAMS_WRITE)
#ifdef VISUAL_POLAR_PARAMS_WRITE
#define VISUAL_POLAR_ACCESS
#else
#define VISUAL_POLAR_ACCESS readonly
#endif
// Written by VisualPolarWarp (core/sampling/VisualPolar.h twin: VisualPolarParamsGpu).
layout(std430) VISUAL_POLAR_ACCESS buffer VisualPolarParams {
    uvec4 grid;    // x W per eye, y H, z eye count, w 1 = valid
    vec4 fovea;    // x rho_f, y e_f, z screen eye width, w screen height
    vec4 eyes[2];  // xy gaze (eye pixels), z dMax
    uvec4 stair;   // x staircase block B (0 = triangular clip), y this frame's block offset x,
                   // z the previous frame's (both < B)
} vp;

VisualPolarMap vpMapOfEye(uint eye) {
    VisualPolarMap m;
    m.screen = max(vp.fovea.zw, vec2(1.0));
    m.gaze = vp.eyes[min(eye, 1u)].xy;
    m.dMax = max(vp.eyes[min(eye, 1u)].z, 0.5);
    m.width = max(vp.grid.x, 1u);
    m.height = max(vp.grid.y, 1u);
    m.foveaFraction = clamp(vp.fovea.x, 0.1, 1.0);  // kVisualPolarMinFoveaFraction
    m.foveaDegrees = max(vp.fovea.y, 1e-3);
    m.stairBlock = vp.stair.x;
    m.stairPhase = vpStairPhaseOf(vp.stair.x, vp.stair.y, min(eye, 1u), m.width);
    m.stairPrevPhase = vpStairPhaseOf(vp.stair.x, vp.stair.z, min(eye, 1u), m.width);
    return m;
}

// The eye whose Visual-Polar image holds column x of the whole (side-by-side) image.
uint vpEyeOfColumn(float x) {
    return min(uint(max(x, 0.0)) / max(vp.grid.x, 1u), clamp(vp.grid.z, 1u, 2u) - 1u);
}

// vpNeighbour in whole-image texels: the neighbour at offset `step` of texel p inside p's eye,
// wrapped on phi at the target column's own height; beyond the rho range ivec2(-1) (off the
// image, so a bounds test skips it, as off the screen's edge).
ivec2 vpImageNeighbour(ivec2 p, ivec2 step) {
    uint eye = vpEyeOfColumn(float(p.x));
    VisualPolarMap m = vpMapOfEye(eye);
    ivec2 x0 = ivec2(int(eye * m.width), 0);
    int column = p.x - x0.x + step.x;
    if (column < 0 || column >= int(m.width)) return ivec2(-1);
    return vpNeighbour(m, p - x0, step) + x0;
}
#endif

#endif
