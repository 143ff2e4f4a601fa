#version 460
// BMFR phase I (seed 003, P2 §3.2): temporal accumulation of the albedo-demodulated noisy
// radiance. The pixel's world position is reprojected into the previous frame (through the
// previous camera, or the `motion` input when connected); each of the 4 bilinear taps there is
// kept only if its stored position and normal pass the discard test, and the colour is
// normalized by the accepted weights only. Cumulative moving average until the new sample's
// weight would fall below `alpha` (0.2), then exponential. Inputs are sanitized here so that NaN,
// Inf or negative values never reach the history (counted in `stats`).
#extension GL_GOOGLE_include_directive : require
#include "bmfr/bmfr_common.glsl"
#include "common/camera.glsl"
#include "bmfr/bmfr_reprojection.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;     // demodulated radiance, a = samples (0 = untraced)
uniform sampler2D position;  // world position, w = 1 hit
uniform sampler2D normal;    // shading normal
uniform sampler2D motion;    // previous pixel - current pixel (optional)
// History ping-pong (bound by the pass): previous frame's slot is read, this frame's written.
layout(rgba32f) uniform readonly image2D prev_hist_position;
layout(rgba16f) uniform readonly image2D prev_hist_normal;
layout(BMFR_HIST_FORMAT) uniform readonly image2D prev_hist_accum;
layout(rgba32f) uniform writeonly image2D hist_position;
layout(rgba16f) uniform writeonly image2D hist_normal;
layout(BMFR_HIST_FORMAT) uniform writeonly image2D hist_accum;
layout(rgba32f) uniform writeonly image2D accumulated;   // rgb mean, a = sample count
layout(rgba32f) uniform writeonly image2D reprojection;  // xy previous pixel, z tap mask, w 1
layout(std430) buffer Stats { uint counters[4]; } stats;

layout(push_constant) uniform Params {
    ivec2 size;
    int history;     // 0: no previous frame (reset, camera cut, first frame)
    int useMotion;   // 1: reproject with the motion input, 0: through the previous camera
    float alpha;     // minimum weight of the new sample (P2 §3.2: 0.2)
    float maxCount;  // sample-count saturation (CMA weight 1 / (n + 1) is below alpha long before)
    float positionThreshold;   // relative to the pixel's distance from the camera
    float normalThreshold;     // minimum cosine between normals
    int useVp;  // 1: a Visual-Polar image (the `vp` block): motion and taps in VP addressing
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;

    vec4 c = texelFetch(color, p, 0);
    vec4 w = texelFetch(position, p, 0);
    vec3 n = texelFetch(normal, p, 0).xyz;

    bool geometryFinite = bmfrFinite4(w) && bmfrFinite3(n);
    if (!geometryFinite) atomicAdd(stats.counters[BMFR_STAT_NONFINITE_GEOMETRY], 1u);
    bool hit = geometryFinite && w.w > 0.0;

    bool sampled = !(c.a <= 0.0);  // a NaN alpha counts as sampled and is caught below
    vec3 x = c.rgb;
    if (sampled && !bmfrFinite4(c)) {
        atomicAdd(stats.counters[BMFR_STAT_NONFINITE_COLOR], 1u);
        sampled = false;  // dropped: the history (if any) is kept for this pixel
    }
    if (sampled && any(lessThan(x, vec3(0.0)))) {
        atomicAdd(stats.counters[BMFR_STAT_NEGATIVE_COLOR], 1u);
        x = max(x, vec3(0.0));  // radiance is non-negative; a negative estimate is invalid input
    }

    // Reprojection (P2 §3.2).
    vec2 prev = vec2(-1.0);
    bool ok = hit && pc.history != 0;
    if (ok) {
        if (pc.useMotion != 0) {
            vec2 m = texelFetch(motion, p, 0).xy;
            ok = bmfrFinite3(vec3(m, 0.0));
            prev = vec2(p) + 0.5 + m;
            if (pc.useVp != 0) {
                // P5 §3.3: motion rows are rows of this texel's column; prev becomes (x, t).
                uint eye = vpEyeOfColumn(float(p.x));
                VisualPolarMap vm = vpMapOfEye(eye);
                ivec2 local = p - ivec2(int(eye * vm.width), 0);
                prev = vpMovedPosition(vm, local, m);
                // Clamped on rho (as the taps are) so that prev.x names this eye's columns only.
                prev.x = clamp(prev.x, 0.5, float(vm.width) - 0.5) + float(eye * vm.width);
            }
        } else {
            ok = cameraPreviousPixel(cameraEyeOf(uint(p.x)), w.xyz, prev);
        }
    }

    vec3 hist = vec3(0.0);
    float count = 0.0;
    uint mask = 0u;
    if (ok) {
        ivec2 taps[4];
        float weights[4];
        bmfrHistoryTaps(pc.useVp != 0, pc.size, prev, taps, weights);
        float wsum = 0.0;
        // The position test scales with the distance to the eye (the pixel footprint grows with
        // it), so the threshold needs no scene units: 1e4 units away or in a 555-unit Cornell box
        // alike. `<=` keeps an identical position at distance 0.
        uint eye = cameraEyeOf(uint(p.x));
        float limit = pc.positionThreshold * length(w.xyz - camera_info.eyes[eye].position.xyz);
        float limit2 = limit * limit;
        for (int i = 0; i < 4; ++i) {
            ivec2 t = taps[i];
            if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, pc.size))) continue;
            vec4 pw = imageLoad(prev_hist_position, t);
            vec3 pn = imageLoad(prev_hist_normal, t).xyz;
            if (!(pw.w > 0.0)) continue;  // no surface there last frame
            vec3 d = pw.xyz - w.xyz;
            if (!(dot(d, d) <= limit2)) continue;
            if (!(dot(pn, n) >= pc.normalThreshold)) continue;
            float bw = weights[i];
            vec4 h = imageLoad(prev_hist_accum, t);
            hist += bw * h.rgb;
            count += bw * h.a;
            wsum += bw;
            mask |= 1u << i;
        }
        // Normalize by the accepted weights only (P2 §3.2). A tap set whose weights sum to almost
        // nothing (prev exactly on a rejected tap's centre) is treated as no history.
        if (wsum > 1e-4) {
            hist /= wsum;
            count /= wsum;
#if !BMFR_UNROUNDED_COUNT
            count = floor(count + 0.5);  // P2: rounded to the closest integer
#endif
        } else {
            hist = vec3(0.0);
            count = 0.0;
            mask = 0u;
        }
    }

    vec3 acc = hist;
    if (sampled) {
        // CMA weight 1 / (n + 1) until it would fall below alpha, then EMA with alpha.
        float a = max(1.0 / (count + 1.0), pc.alpha);  // count >= 0
        acc = mix(hist, x, a);
        // Published (bmfr.cl accumulate_noisy_data): the weight above uses the interpolated
        // count; only the stored count is rounded (to nearest even, convert_uchar_sat_rte).
        count = min(roundEven(count) + 1.0, pc.maxCount);
    } else {
        count = roundEven(count);  // unsampled: the interpolated history count, rounded
    }
    // Belt and braces: history only ever holds finite values.
    if (!bmfrFinite3(acc)) { acc = vec3(0.0); count = 0.0; }
    acc = min(acc, vec3(BMFR_HIST_MAX));  // the output equals what the history keeps

    imageStore(accumulated, p, vec4(acc, count));
    imageStore(hist_accum, p, vec4(acc, count));
    imageStore(hist_position, p, hit ? w : vec4(0.0));
    imageStore(hist_normal, p, vec4(hit ? n : vec3(0.0), 0.0));
    imageStore(reprojection, p, vec4(prev, float(mask), 1.0));
}
