#version 460
// TAA (Karis 2014, "High Quality Temporal Supersampling"; used as the last stage of seed 003 P2
// §3 / Fig. 2 and thesis §3.6): reproject the previous result with the motion vectors, sample it
// bilinearly or with Catmull-Rom, constrain it to the current 3x3 neighbourhood in YCoCg
// (min/max box clip, or Salvi 2016 variance clipping mu +- gamma sigma), then blend
//   result = mix(history, current, alpha).
// Jitter: the motion vector is jitter-free (camera.glsl: a still camera gives exactly 0), so the
// history is fetched at the un-jittered pixel centre p + 0.5 + motion. The current sample stays
// at its jittered position on purpose: averaging samples taken at the 16 Halton offsets over a
// pixel is the supersampling that antialiases (Karis 2014). See docs/passes/TAA.md.
// Stereo: every tap (neighbourhood and history) stays inside the eye of the pixel; a history
// position in the other eye counts as off-screen (no history).
#extension GL_GOOGLE_include_directive : require
#include "common/color.glsl"
#define VISUAL_POLAR_PARAMS
#include "common/visual_polar.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;
uniform sampler2D motion;
uniform sampler2D prev_result;  // our own result of the previous frame (pass-declared history)
layout(rgba32f) uniform writeonly image2D result;

layout(push_constant) uniform Params {
    ivec2 size;       // the whole (side-by-side) image
    int eyeWidth;     // >= 1 (the pass clamps it); the last eye takes the remainder
    int eyes;         // 1 or 2
    float alpha;      // weight of the current frame, [0, 1]
    int clipMode;     // 0 none, 1 min/max box, 2 variance box
    float gamma;      // variance box half-width in standard deviations
    int catmullRom;   // 1: Catmull-Rom history, 0: bilinear
    int useHistory;   // 0 on the first frame after a reset / camera cut (history invalid)
    int useMotion;    // 0: no motion input (still camera)
    int useVp;        // 1: a Visual-Polar image (the `vp` block): VP neighbours and history taps
} pc;

// YCoCg (Malvar & Sullivan): the clip box is tighter around a colour cluster than in RGB
// (Karis 2014). Exact inverse below, no division.
vec3 toYCoCg(vec3 c) {
    return vec3(0.25 * c.r + 0.5 * c.g + 0.25 * c.b, 0.5 * c.r - 0.5 * c.b,
                -0.25 * c.r + 0.5 * c.g - 0.25 * c.b);
}
vec3 fromYCoCg(vec3 c) { return vec3(c.x + c.y - c.z, c.x + c.z, c.x - c.y - c.z); }

// The current image at an integer position inside [lo, hi] (the pixel's eye), NaN/Inf -> 0 so a
// bad input pixel can never reach the history (it only ever gets blended as 0).
vec4 current(ivec2 q, ivec2 lo, ivec2 hi) {
    return sanitize(texelFetch(color, clamp(q, lo, hi), 0));
}
vec3 historyTap(ivec2 q, ivec2 lo, ivec2 hi) {
    // History is our own output, sanitized when stored; sanitizing again costs little and keeps a
    // NaN from ever spreading should that invariant break.
    return sanitize(texelFetch(prev_result, clamp(q, lo, hi), 0)).rgb;
}

// Bilinear history at image position h (pixel centres at +0.5), taps clamped to the eye.
vec3 historyBilinear(vec2 h, ivec2 lo, ivec2 hi) {
    vec2 f = h - 0.5;
    ivec2 i = ivec2(floor(f));
    vec2 t = f - vec2(i);
    vec3 a = mix(historyTap(i, lo, hi), historyTap(i + ivec2(1, 0), lo, hi), t.x);
    vec3 b = mix(historyTap(i + ivec2(0, 1), lo, hi), historyTap(i + ivec2(1, 1), lo, hi), t.x);
    return mix(a, b, t.y);
}

// Catmull-Rom weights of the 4 taps around t in [0,1); they sum to 1 exactly in real arithmetic.
vec4 catmullRomWeights(float t) {
    float t2 = t * t, t3 = t2 * t;
    return vec4(-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0, -1.5 * t3 + 2.0 * t2 + 0.5 * t,
                0.5 * t3 - 0.5 * t2);
}

// Catmull-Rom history: 16 taps, each clamped to the eye (not the 9-tap bilinear trick, whose
// hardware-filtered taps could straddle the eye seam). May overshoot: the clip below bounds it.
vec3 historyCatmullRom(vec2 h, ivec2 lo, ivec2 hi) {
    vec2 f = h - 0.5;
    ivec2 i = ivec2(floor(f));
    vec2 t = f - vec2(i);
    vec4 wx = catmullRomWeights(t.x), wy = catmullRomWeights(t.y);
    vec3 sum = vec3(0.0);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            sum += wx[x] * wy[y] * historyTap(i + ivec2(x - 1, y - 1), lo, hi);
    return sum;
}

// Visual-Polar history (seed 003 P5 §3.3): bilinear at the continuous position `h` (eye-local
// x in columns, t = phi / 2 pi), each column at its own phi height, wrapped on phi. `m` carries
// the previous frame's heights (vpPrevious: the staircase moves every frame).
vec3 historyVisualPolar(VisualPolarMap m, vec2 h, int x0, ivec2 lo, ivec2 hi) {
    ivec2 taps[4];
    float weights[4];
    vpBilinearTaps(m, h, taps, weights);
    vec3 sum = vec3(0.0);
    for (int k = 0; k < 4; ++k) sum += weights[k] * historyTap(taps[k] + ivec2(x0, 0), lo, hi);
    return sum;
}

// Catmull-Rom on a Visual-Polar image (P5 §3.3): 4 columns around h.x (clamped on rho), and in
// each column 4 rows around h.y = t at that column's OWN phi height, wrapped on phi; the row
// weights are per column. 16 taps like the screen version; `m` has the previous frame's heights.
vec3 historyVisualPolarCatmullRom(VisualPolarMap m, vec2 h, int x0, ivec2 lo, ivec2 hi) {
    float x = h.x - 0.5;
    float c1f = floor(x);
    vec4 wx = catmullRomWeights(x - c1f);
    vec3 sum = vec3(0.0);
    for (int a = 0; a < 4; ++a) {
        int c = clamp(int(c1f) - 1 + a, 0, int(m.width) - 1);
        int n = int(vpRows(m, uint(c)));  // >= 1
        float y = fract(h.y) * float(n) - 0.5;
        float r1f = floor(y);  // >= -1
        vec4 wy = catmullRomWeights(y - r1f);
        for (int b = 0; b < 4; ++b) {
            int r = ((int(r1f) - 1 + b) % n + n) % n;
            sum += wx[a] * wy[b] * historyTap(ivec2(c + x0, r), lo, hi);
        }
    }
    return sum;
}

// Moves `h` along the line towards `centre` until it lies in the box centre +- extent (Karis 2014
// clip; unlike a per-channel clamp it keeps the hue of the history). extent >= 0. Divisions only
// happen where |v| > extent >= 0, so |v| > 0; a zero-size box yields the centre.
vec3 clipToBox(vec3 h, vec3 centre, vec3 extent) {
    vec3 v = h - centre;
    vec3 av = abs(v);
    float s = 1.0;
    for (int k = 0; k < 3; ++k)
        if (av[k] > extent[k]) s = min(s, extent[k] / av[k]);
    return centre + v * s;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;

    // The pixel's eye: columns [x0, x1] (the last eye takes the remainder of an odd width).
    int eye = min(p.x / pc.eyeWidth, pc.eyes - 1);  // eyeWidth >= 1
    int x0 = eye * pc.eyeWidth;
    int x1 = eye == pc.eyes - 1 ? pc.size.x - 1 : x0 + pc.eyeWidth - 1;
    ivec2 lo = ivec2(x0, 0), hi = ivec2(x1, pc.size.y - 1);

    vec4 c = current(p, lo, hi);

    VisualPolarMap m;
    if (pc.useVp != 0) m = vpMapOfEye(uint(eye));

    // 3x3 neighbourhood statistics in YCoCg (taps clamped to the eye: no seam crossing). On a
    // Visual-Polar image the neighbours wrap on phi and follow each column's phi height (P5
    // §3.3: a row index is a different phi in columns of different heights).
    vec3 mn = vec3(3.0e38), mx = vec3(-3.0e38), m1 = vec3(0.0), m2 = vec3(0.0);
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = p + ivec2(dx, dy);
            if (pc.useVp != 0) q = vpNeighbour(m, p - ivec2(x0, 0), ivec2(dx, dy)) + ivec2(x0, 0);
            vec3 s = toYCoCg(current(q, lo, hi).rgb);
            mn = min(mn, s);
            mx = max(mx, s);
            m1 += s;
            m2 += s * s;
        }

    // Reprojection. A NaN/Inf motion (or one beyond any image) counts as off-screen.
    vec2 mv = pc.useMotion != 0 ? texelFetch(motion, p, 0).xy : vec2(0.0);
    vec2 h = vec2(p) + 0.5 + mv;
    bool onScreen = !any(isnan(mv)) && !any(isinf(mv)) && h.x >= float(x0) &&
                    h.x < float(x1 + 1) && h.y >= 0.0 && h.y < float(pc.size.y);

    if (pc.useVp != 0) {
        // Motion in columns and rows of this texel's column (GBuffer): h becomes (x, t), eye-
        // local; phi always exists, rho must stay inside the grid.
        h = vpMovedPosition(m, p - ivec2(x0, 0), mv);
        onScreen = !any(isnan(h)) && !any(isinf(h)) && h.x >= 0.0 && h.x < float(m.width);
    }

    vec3 outColor = c.rgb;  // no history: the current frame alone (alpha = 1)
    if (pc.useHistory != 0 && onScreen) {
        // Visual-Polar history at the previous frame's phi heights (vpPrevious: the staircase
        // moves every frame), Catmull-Rom with per-column row sets or bilinear.
        vec3 hc;
        if (pc.useVp != 0)
            hc = pc.catmullRom != 0 ? historyVisualPolarCatmullRom(vpPrevious(m), h, x0, lo, hi)
                                    : historyVisualPolar(vpPrevious(m), h, x0, lo, hi);
        else
            hc = pc.catmullRom != 0 ? historyCatmullRom(h, lo, hi) : historyBilinear(h, lo, hi);
        vec3 hy = toYCoCg(hc);
        if (pc.clipMode == 1) {
            hy = clipToBox(hy, 0.5 * (mn + mx), 0.5 * (mx - mn));
        } else if (pc.clipMode == 2) {
            // Salvi 2016: box mu +- gamma * sigma. var >= 0 mathematically; max() absorbs the
            // rounding of E[x^2] - E[x]^2 so sqrt never sees a negative number.
            vec3 mu = m1 / 9.0;
            vec3 sigma = sqrt(max(m2 / 9.0 - mu * mu, vec3(0.0)));
            hy = clipToBox(hy, mu, pc.gamma * sigma);
        }
        outColor = mix(fromYCoCg(hy), c.rgb, pc.alpha);
    }
    // Finite inputs give a finite result except for overflow near 3e38; sanitize so NaN/Inf can
    // never enter the history that the next frame reads.
    imageStore(result, p, sanitize(vec4(outColor, c.a)));
}
