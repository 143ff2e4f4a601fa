// Normalized hit distance of the split signals (issue 26; seed 004 "Cooking specular denoiser":
// denoisers take saturate(hitT / maxHitT), NRD REBLUR_FrontEnd_GetNormHitDist). maxHitT grows
// with the view distance and, for smooth lobes, with a roughness factor:
//   maxHitT = frustumSize(z) * mix(1, kHitDistanceSmoothBoost, 2^(kHitDistanceRoughFalloff r^2)),
//   frustumSize(z) = 2 tan(fovY / 2) z  (the view's height at depth z, as RecurrentBlur's diffuse
//   normalization, so a diffuse signal normalizes the same way in both).
// NRD's hitDistanceParameters are {A = 3 m, B = 0.1, C = 20, D = -25} with maxHitT = (A + B z)
// * mix(1, C, 2^(D r^2)); we keep C and D and replace A + B z by the frustum size, which needs
// no scene unit (builtin:cornell is in millimetres). A rough lobe (r = 1) gets the plain frustum
// size (2^-25 ~ 3e-8), a mirror 20 x it: reflections see far.
#ifndef FOVEA_HIT_DISTANCE_GLSL
#define FOVEA_HIT_DISTANCE_GLSL

const float kHitDistanceSmoothBoost = 20.0;    // NRD hitDistanceParameters.C
const float kHitDistanceRoughFalloff = -25.0;  // NRD hitDistanceParameters.D

// maxHitT at view depth z > 0 for linear roughness r (diffuse: 1); > 0 when z > 0.
float hitDistanceScale(float tanHalfFov, float z, float roughness) {
    float r = clamp(roughness, 0.0, 1.0);
    return 2.0 * tanHalfFov * z * mix(1.0, kHitDistanceSmoothBoost,
                                      exp2(kHitDistanceRoughFalloff * r * r));
}

// saturate(t / scale); t <= 0, NaN or inf (no hit) is far: 1.
float normalizeHitDistance(float t, float scale) {
    if (!(t > 0.0) || isinf(t) || !(scale > 0.0)) return 1.0;
    return clamp(t / scale, 0.0, 1.0);  // scale > 0
}

// The inverse for h < 1 (h = 1 means "at least scale": returns scale).
float denormalizeHitDistance(float h, float scale) { return clamp(h, 0.0, 1.0) * scale; }

#endif
