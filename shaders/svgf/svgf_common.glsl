// Shared by the SVGF kernels (Schied et al. 2017, "Spatiotemporal Variance-Guided Filtering";
// docs/references.md, docs/passes/SVGF.md): guarded reads of the G-buffer, the depth
// gradient and the edge-stopping weights (paper §4.4). Every read is clamped to the image (an
// out-of-bounds imageLoad is undefined in Vulkan, specs §1 F7).
#ifndef FOVEA_SVGF_COMMON_GLSL
#define FOVEA_SVGF_COMMON_GLSL

#include "common/color.glsl"

// Counters of the `stats` buffer (uint[5]): docs/passes/SVGF.md#stats.
#define SVGF_STAT_NONFINITE_COLOR 0
#define SVGF_STAT_NONFINITE_GEOMETRY 1
#define SVGF_STAT_REJECTED 2
#define SVGF_STAT_SPATIAL_VARIANCE 3
#define SVGF_STAT_NEGATIVE_VARIANCE 4

// A colour sample larger than this is clamped so that l^2 (the second moment) stays finite in
// fp32 (3.4e38); real radiance is many orders of magnitude below.
#define SVGF_MAX_SAMPLE 1.0e15

bool svgfFinite(float v) { return !isnan(v) && !isinf(v); }
bool svgfFinite3(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }
bool svgfFinite4(vec4 v) { return !any(isnan(v)) && !any(isinf(v)); }

ivec2 svgfClamp(ivec2 q, ivec2 size) { return clamp(q, ivec2(0), size - 1); }  // size >= 1

// Linear view depth of a surface, 0 for a miss or an unusable (non-finite, negative) value.
float svgfDepthAt(sampler2D depthTex, ivec2 q) {
    float z = texelFetch(depthTex, q, 0).x;
    return (svgfFinite(z) && z > 0.0) ? z : 0.0;
}

// Shading normal, or zero when missing or non-finite (then the pixel is treated as a miss).
vec3 svgfNormalAt(sampler2D normalTex, ivec2 q) {
    vec3 n = texelFetch(normalTex, q, 0).xyz;
    return svgfFinite3(n) ? n : vec3(0.0);
}

// The texel one step away: screen addressing, or on a Visual-Polar image (useVp, where the
// including shader has the `vp` block) the neighbour wrapped on phi at the target column's own
// height (P5 §3.3; ivec2(-1) beyond the rho range, which the bounds test rejects).
ivec2 svgfStep(ivec2 p, ivec2 step, bool useVp) {
#ifdef VISUAL_POLAR_PARAMS
    if (useVp) return vpImageNeighbour(p, step);
#endif
    return p + step;
}

// Image-space depth gradient at p (specs §1: per axis the one-sided difference with the smaller
// magnitude, so a silhouette does not inflate it); 0 along an axis without a surface neighbour.
// On a Visual-Polar image the axes are rho (columns) and phi (rows of p's column), the units the
// a-trous offsets are in.
vec2 svgfDepthGradient(sampler2D depthTex, ivec2 p, ivec2 size, float zp, bool useVp) {
    vec2 g = vec2(0.0);
    for (int a = 0; a < 2; ++a) {
        ivec2 e = a == 0 ? ivec2(1, 0) : ivec2(0, 1);
        bool found = false;
        float best = 0.0;
        for (int s = -1; s <= 1; s += 2) {
            ivec2 q = svgfStep(p, s * e, useVp);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
            float zq = svgfDepthAt(depthTex, q);
            if (zq <= 0.0) continue;
            float d = float(s) * (zq - zp);
            if (!found || abs(d) < abs(best)) best = d;
            found = true;
        }
        g[a] = best;
    }
    return g;
}

// Paper §4.4 edge-stopping weights. Depth: exp(-|zp - zq| / (sigmaZ |grad z . offset| + eps));
// eps is relative to zp (1e-5 zp), so fp32 rounding on a plane facing the camera (gradient 0)
// does not reject equal depths. zp > 0 here (misses never reach the weights).
float svgfDepthWeight(float zp, float zq, vec2 grad, vec2 offset, float sigmaZ) {
    float den = sigmaZ * abs(dot(grad, offset)) + 1e-5 * zp;  // > 0 because zp > 0
    return exp(-abs(zp - zq) / den);
}

// max(0, np . nq)^sigmaN; sigmaN = 0 turns the term off (pow(0, 0) is undefined in GLSL).
float svgfNormalWeight(vec3 np, vec3 nq, float sigmaN) {
    if (sigmaN <= 0.0) return 1.0;
    return pow(max(0.0, dot(np, nq)), sigmaN);  // base >= 0, exponent > 0: defined
}

#endif
