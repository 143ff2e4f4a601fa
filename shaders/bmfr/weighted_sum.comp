#version 460
// BMFR phase II, weighted sum (seed 003, P2 Eq. 3/6): each pixel evaluates its block's fitted
// coefficients on the NOISE-FREE features (the regularization noise only entered the fit).
// The result is clamped at 0 (radiance is non-negative), as the published code (bmfr.cl
// weighted_sum) does; with BMFR_CLAMP_BLOCKMAX also at the block max of z, since a least-squares
// fit of data in [0, zmax] leaves that range only by extrapolation. With BMFR_FIT_MISSES the fit
// is evaluated on misses too (published).
#extension GL_GOOGLE_include_directive : require
#define BMFR_BLOCK_GRID_VP
#include "bmfr/bmfr_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D accumulated;
uniform sampler2D position;
uniform sampler2D normal;
#if BMFR_ALBEDO
uniform sampler2D albedo;  // a feature only with features = albedo
#endif
layout(std430) buffer Coefficients { float v[]; } coefficients;
layout(rgba32f) uniform writeonly image2D fitted;

layout(push_constant) uniform Params {
    ivec2 size;
    ivec2 offset;
    int blocksX;
    int useVp;  // 1: the `vp` block may move the block columns (bmfrBlockOffset)
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    vec4 z = texelFetch(accumulated, p, 0);
    vec4 w = texelFetch(position, p, 0);
    vec3 n = texelFetch(normal, p, 0).xyz;
    vec3 a = vec3(0.0);
#if BMFR_ALBEDO
    a = texelFetch(albedo, p, 0).rgb;
    if (!bmfrFinite3(a)) a = vec3(0.0);
    a = clamp(a, 0.0, 1.0);
#endif
    // Pixels the fit did not use (miss, non-finite geometry) keep their accumulated value.
    vec3 y = z.rgb;
#if BMFR_FIT_MISSES
    bool useFit = true;
#else
    bool useFit = w.w > 0.0;
#endif
    if (useFit && bmfrFinite3(w.xyz) && bmfrFinite3(n)) {
        ivec2 q = p + bmfrBlockOffset(pc.offset, pc.useVp);  // offset >= 0, so q >= 0
        int block = (q.y / BMFR_BLOCK) * pc.blocksX + q.x / BMFR_BLOCK;
        int base = block * BMFR_COEF_STRIDE;
        vec3 center, invHalf, zMax;
        for (int c = 0; c < 3; ++c) {
            center[c] = coefficients.v[base + BMFR_COEF_CENTER + c];
            invHalf[c] = coefficients.v[base + BMFR_COEF_INVHALF + c];
            zMax[c] = coefficients.v[base + BMFR_COEF_ZMAX + c];
        }
        float f[BMFR_M];
        bmfrFeatures(w.xyz, clamp(n, -1.0, 1.0), a, center, invHalf, f);
        vec3 s = vec3(0.0);
        for (int m = 0; m < BMFR_M; ++m) {
            float g = m == 0 ? 1.0
                             : bmfrScale(f[m], coefficients.v[base + BMFR_COEF_FMID + m],
                                         coefficients.v[base + BMFR_COEF_FINV + m]);
            s += g * vec3(coefficients.v[base + m * 3 + 0],
                             coefficients.v[base + m * 3 + 1],
                             coefficients.v[base + m * 3 + 2]);
        }
#if BMFR_CLAMP_BLOCKMAX
        vec3 upper = zMax;
#else
        vec3 upper = vec3(BMFR_HIST_MAX);  // only the finite limit of the history format
#endif
        y = bmfrFinite3(s) ? clamp(s, vec3(0.0), upper) : z.rgb;
    }
    if (!bmfrFinite3(y)) y = vec3(0.0);
    imageStore(fitted, p, vec4(y, z.a));
}
