#version 460
// BMFR phase III (seed 003, P2 §3.5): second temporal accumulation of the fitted frame, reusing
// phase I's reprojection and per-tap discard decisions (no position/normal reloads), CMA until
// the new weight would fall below `alpha` (0.1), then EMA. Then remodulation (CONTRACT):
// filtered = x * albedo' + emission, albedo' = albedo where > 1e-3 else 1, per channel.
#extension GL_GOOGLE_include_directive : require
#include "bmfr/bmfr_common.glsl"
#include "common/color.glsl"
#include "bmfr/bmfr_reprojection.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D fitted;
uniform sampler2D reprojection;
uniform sampler2D albedo;
uniform sampler2D emission;
layout(BMFR_HIST_FORMAT) uniform readonly image2D prev_hist_filtered;
layout(BMFR_HIST_FORMAT) uniform writeonly image2D hist_filtered;
layout(rgba32f) uniform writeonly image2D filtered;

layout(push_constant) uniform Params {
    ivec2 size;
    int useAlbedo;
    int useEmission;
    float alpha;     // P2 §3.5: 0.1
    float maxCount;
    int useVp;  // 1: a Visual-Polar image: rp.xy is (x, t = phi / 2 pi), VP taps
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    vec3 x = texelFetch(fitted, p, 0).rgb;  // finite (weighted_sum.comp)
    vec4 rp = texelFetch(reprojection, p, 0);
    uint mask = uint(rp.z);  // 0..15, exact in float

    vec3 hist = vec3(0.0);
    float count = 0.0;
    if (mask != 0u) {
        // Finite: mask != 0 means phase I accepted a tap here (and computed the same taps).
        ivec2 taps[4];
        float weights[4];
        bmfrHistoryTaps(pc.useVp != 0, pc.size, rp.xy, taps, weights);
        float wsum = 0.0;
        for (int i = 0; i < 4; ++i) {
            if ((mask & (1u << i)) == 0u) continue;
            float bw = weights[i];
            vec4 h = imageLoad(prev_hist_filtered, taps[i]);  // in bounds: phase I checked it
            hist += bw * h.rgb;
            count += bw * h.a;
            wsum += bw;
        }
        if (wsum > 1e-4) {  // phase I kept the mask only with wsum > 1e-4
            hist /= wsum;
            count = floor(count / wsum + 0.5);
        } else {
            hist = vec3(0.0);
            count = 0.0;
        }
    }
    float a = max(1.0 / (count + 1.0), pc.alpha);  // count >= 0
    vec3 y = mix(hist, x, a);
    count = min(count + 1.0, pc.maxCount);
    if (!bmfrFinite3(y)) { y = vec3(0.0); count = 0.0; }
    y = min(y, vec3(BMFR_HIST_MAX));
    imageStore(hist_filtered, p, vec4(y, count));

    vec3 alb = vec3(1.0), emi = vec3(0.0);
    if (pc.useAlbedo != 0) {
        // NaN and Inf fall back to 1 (as a miss would).
        alb = demodulationAlbedo(texelFetch(albedo, p, 0).rgb);
    }
    if (pc.useEmission != 0) {
        emi = texelFetch(emission, p, 0).rgb;
        if (!bmfrFinite3(emi)) emi = vec3(0.0);
    }
    vec3 outc = y * alb + emi;
    if (!bmfrFinite3(outc)) outc = y;  // albedo' is finite here, so only an overflow: keep y
    imageStore(filtered, p, vec4(outc, 1.0));
}
