// The colour spaces of ꟻLIP (Andersson et al. 2020, "FLIP: A Difference Evaluator for
// Alternating Images", HPG 2020, the colour pipeline): sRGB, linear RGB (sRGB primaries), CIE
// XYZ under D65, the linearized opponent space YyCxCz in which the contrast sensitivity filters
// run, and CIE L*a*b*, plus the Hunt adjustment and the HyAB distance. Header-only: these run
// per pixel.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>

namespace fovea::eval::flip {

using Color = std::array<float, 3>;

// D65 reference white in XYZ (Y = 1): YyCxCz and L*a*b* divide by it.
inline constexpr Color kD65White = {0.950428545f, 1.0f, 1.088900371f};

// sRGB transfer function (IEC 61966-2-1), decode: display value in [0,1] -> linear.
inline float srgbToLinear(float c) {
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Linear RGB with sRGB primaries -> XYZ (D65) and back. The forward matrix is FLIP's (rows of
// exact fractions, 10135552/24577794, ..., within 2e-5 of IEC 61966-2-1's rounded matrix), whose
// rows sum to the white point (Xn, 1, Zn) exactly; the inverse is its exact inverse, so a round
// trip returns the input to float precision.
inline Color linearRgbToXyz(const Color& c) {
    return {0.412386563f * c[0] + 0.357591491f * c[1] + 0.180450491f * c[2],
            0.212636822f * c[0] + 0.715182982f * c[1] + 0.072180196f * c[2],
            0.019330620f * c[0] + 0.119197164f * c[1] + 0.950372587f * c[2]};
}
inline Color xyzToLinearRgb(const Color& c) {
    return {3.241003233f * c[0] - 1.537398969f * c[1] - 0.498615882f * c[2],
            -0.969224252f * c[0] + 1.875929984f * c[1] + 0.041554226f * c[2],
            0.055639420f * c[0] - 0.204011206f * c[1] + 1.057148977f * c[2]};
}

// YyCxCz: L*a*b* without the cube root, so that it is linear in XYZ and can be filtered
// (FLIP's colour pipeline; Y_y = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn), Cz = 200 (Y/Yn - Z/Zn)).
inline Color xyzToYcxcz(const Color& c) {
    const float x = c[0] / kD65White[0], y = c[1], z = c[2] / kD65White[2];
    return {116.0f * y - 16.0f, 500.0f * (x - y), 200.0f * (y - z)};
}
inline Color ycxczToXyz(const Color& c) {
    const float y = (c[0] + 16.0f) / 116.0f;
    return {(y + c[1] / 500.0f) * kD65White[0], y, (y - c[2] / 200.0f) * kD65White[2]};
}

// CIE L*a*b* (CIE 15:2004) under D65, with the linear segment below (6/29)^3.
inline float labF(float t) {
    constexpr float kDelta = 6.0f / 29.0f;
    return t > kDelta * kDelta * kDelta ? std::cbrt(t)
                                        : t / (3.0f * kDelta * kDelta) + 4.0f / 29.0f;
}
inline Color xyzToLab(const Color& c) {
    const float fx = labF(c[0] / kD65White[0]), fy = labF(c[1]), fz = labF(c[2] / kD65White[2]);
    return {116.0f * fy - 16.0f, 500.0f * (fx - fy), 200.0f * (fy - fz)};
}

// FLIP's colour pipeline: the Hunt effect (chroma appears weaker at low luminance): a and b scaled
// by 0.01 L.
inline Color huntAdjust(const Color& lab) {
    return {lab[0], 0.01f * lab[0] * lab[1], 0.01f * lab[0] * lab[2]};
}

// FLIP's colour metric (Abasi et al. 2020): HyAB = |ΔL| + ||(Δa, Δb)||, a city-block lightness term
// plus a Euclidean chroma term; better than ΔE for large colour differences.
inline float hyab(const Color& a, const Color& b) {
    const float da = a[1] - b[1], db = a[2] - b[2];
    return std::abs(a[0] - b[0]) + std::sqrt(da * da + db * db);
}

// Linear RGB -> Hunt-adjusted L*a*b*, clamped to the unit cube first (FLIP clamps the filtered
// image to [0,1] in linear RGB before L*a*b*: the filters can leave the gamut).
inline Color linearRgbToHuntLab(Color rgb) {
    for (float& v : rgb) v = std::clamp(v, 0.0f, 1.0f);
    return huntAdjust(xyzToLab(linearRgbToXyz(rgb)));
}

}  // namespace fovea::eval::flip
