// Shared helpers of the RecurrentBlur stages (seed 004, the ReBLUR talk; NRD defaults in
// docs/passes/RecurrentBlur.md). Every stage keeps its taps inside the pixel's eye.
#ifndef FOVEA_REBLUR_COMMON_GLSL
#define FOVEA_REBLUR_COMMON_GLSL

// Columns [lo.x, hi.x] x rows [0, hi.y] of the eye that holds pixel p (side-by-side stereo);
// eyeWidth >= 1 (the pass clamps it), the last eye takes the remainder of an odd width.
void eyeBounds(ivec2 p, ivec2 size, int eyeWidth, int eyes, out ivec2 lo, out ivec2 hi) {
    int eye = min(p.x / eyeWidth, eyes - 1);
    int x0 = eye * eyeWidth;
    int x1 = eye == eyes - 1 ? size.x - 1 : x0 + eyeWidth - 1;
    lo = ivec2(x0, 0);
    hi = ivec2(x1, size.y - 1);
}

// NRD's non-exponential weight 1 - smoothstep(0, 1, |x|) (specs §2 "Definitions").
float reblurWeight(float x) { return 1.0 - smoothstep(0.0, 1.0, abs(x)); }

// Frustum size at view depth z: 2 tan(fovY/2) z (specs §2; NRD GetFrustumSize). z > 0 here.
float frustumSize(float tanHalfFov, float z) { return 2.0 * tanHalfFov * z; }

// Normalized hit distance h = saturate(d / frustumSize) in [0, 1]. d = 0 means "the indirect ray
// hit nothing" (PathTrace.hit_distance): that is FAR (h = 1), never contact (seed 004 / specs §2
// failure modes: treating it as 0 would shrink the radius and the weights). A non-finite or
// negative d is treated the same way. frustum > 0 (guarded by the caller's z > 0).
float normalizedHit(float d, float frustum) {
    if (!(d > 0.0) || isinf(d)) return 1.0;
    return clamp(d / max(frustum, 1e-20), 0.0, 1.0);
}

// Linear step: 0 below a, 1 above b; a < b is required (the caller guards b - a > 0).
float linearStep(float a, float b, float x) { return clamp((x - a) / (b - a), 0.0, 1.0); }

// Radius scale s' of the blur (seed 004: "radius scale 1/(1+N)"; specs §2 "Radius"): the boost
// keeps the full radius while HistoryFix still works on the pixel (N < 2/3 Nhf) and fades over
// [2/3, 4/3] Nhf, stronger at grazing angles. Nhf = 0 disables the boost.
float radiusScale(float n, float historyFixFrames, float nov) {
    float boost = 0.0;
    if (historyFixFrames > 0.0)
        boost = (1.0 - linearStep(historyFixFrames * (2.0 / 3.0), historyFixFrames * (4.0 / 3.0), n)) *
                (1.0 - pow(clamp(1.0 - nov, 0.0, 1.0), 5.0));
    return 1.0 / (1.0 + max(n, 0.0) * (1.0 - boost));  // >= 1 in the denominator
}

#endif
