#version 460
// SVGF variance estimate (Schied et al. 2017 §4.2; specs §1 step 3). var = max(0, mu2 - mu1^2)
// from the temporally accumulated luminance moments; while the history is short (h below
// `historyForVariance`) the moments are too few, so colour and moments are replaced by a
// cross-bilateral average over a (2r+1)^2 window and the variance is scaled by 4/h (Falcor's
// boost of young pixels). The variance is clamped >= 0 before anyone takes its square root
// (specs §1 F2; clamps counted in `stats`).
// The window is weighted by depth and normal only. Falcor adds a luminance term
// exp(-|l_p - l_q| / sigma_l) on the absolute radiance scale; it removes exactly the dissimilar
// samples whose spread this estimate measures, so on heavy-tailed noise (a few bright samples
// among dark ones: the forest's 80 lights at 1 spp) a dark pixel saw zero variance, the bright
// ones kept their value, and the window average lost 30-45 % of the energy in the first frames
// (issue 12, docs/benchmarks.md "SVGF energy loss"). It also made sigma_l depend on the scene's
// radiance units.
#extension GL_GOOGLE_include_directive : require
#define VISUAL_POLAR_PARAMS
#include "common/visual_polar.glsl"
#include "svgf/svgf_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D normal;
uniform sampler2D depth;
layout(rgba32f) uniform readonly image2D accumulated;  // rgb C, a = h
layout(rg32f) uniform readonly image2D hist_moments;   // this frame's moments
layout(rgba32f) uniform writeonly image2D atrous_out;  // rgb C, a = variance
layout(std430) buffer Stats { uint counters[5]; } stats;

layout(push_constant) uniform Params {
    ivec2 size;
    int radius;
    float historyForVariance;
    float sigmaNormal;
    float sigmaDepth;
    int useVp;  // 1: a Visual-Polar image: taps through vpNeighbour (phi wrapped, per-column
                // heights; P5 §3.3)
} pc;

// The tap at offset `off` from texel p: screen addressing, or on a Visual-Polar image the
// neighbour wrapped on phi at the target column's own height (visual_polar.glsl).
ivec2 svgfTap(ivec2 p, ivec2 off) {
    return pc.useVp == 0 ? p + off : vpImageNeighbour(p, off);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;

    vec4 acc = imageLoad(accumulated, p);
    float h = acc.a;
    vec2 m = imageLoad(hist_moments, p).xy;
    float zp = svgfDepthAt(depth, p);
    vec3 np = svgfNormalAt(normal, p);
    if (h <= 0.0 || zp <= 0.0) {  // miss or no data yet: nothing to estimate
        imageStore(atrous_out, p, vec4(acc.rgb, 0.0));
        return;
    }
    vec3 C = acc.rgb;
    if (h < pc.historyForVariance) {
        atomicAdd(stats.counters[SVGF_STAT_SPATIAL_VARIANCE], 1u);
        vec2 grad = svgfDepthGradient(depth, p, pc.size, zp, pc.useVp != 0);
        vec3 sumC = vec3(0.0);
        vec2 sumM = vec2(0.0);
        float sumW = 0.0;
        for (int dy = -pc.radius; dy <= pc.radius; ++dy)
            for (int dx = -pc.radius; dx <= pc.radius; ++dx) {
                ivec2 q = svgfTap(p, ivec2(dx, dy));
                if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, pc.size))) continue;
                vec4 aq = imageLoad(accumulated, q);
                float zq = svgfDepthAt(depth, q);
                if (aq.a <= 0.0 || zq <= 0.0) continue;  // no data / miss: weight 0
                float wgt = 1.0;
                if (dx != 0 || dy != 0) {
                    wgt = svgfDepthWeight(zp, zq, grad, vec2(dx, dy), pc.sigmaDepth) *
                          svgfNormalWeight(np, svgfNormalAt(normal, q), pc.sigmaNormal);
                }
                sumC += wgt * aq.rgb;
                sumM += wgt * imageLoad(hist_moments, q).xy;
                sumW += wgt;
            }
        // sumW >= 1: the centre passed the tests above and has weight 1.
        C = sumC / sumW;
        m = sumM / sumW;
    }
    float var = m.y - m.x * m.x;
    if (var < 0.0) atomicAdd(stats.counters[SVGF_STAT_NEGATIVE_VARIANCE], 1u);
    var = max(var, 0.0);
    if (h < pc.historyForVariance) var *= 4.0 / h;  // h > 0 here
    imageStore(atrous_out, p, sanitize(vec4(C, var)));
}
