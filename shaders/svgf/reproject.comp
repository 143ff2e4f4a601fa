#version 460
// SVGF temporal accumulation (Schied et al. 2017 §4.1; specs §1 steps 1-2). The pixel is
// reprojected (motion input, or its world position through the previous camera); each of the 4
// bilinear taps is kept when it is inside the image, held data last frame, and its stored world
// position and normal agree with the pixel's. History colour, moments and length are blended over
// the kept taps with renormalized weights; when their weights sum below 0.01 the mean of the valid
// taps of the 3x3 around the reprojected pixel is taken; else the pixel restarts (h = 1).
// h is the weighted AVERAGE of the kept taps' lengths (a max ghosts: specs §5 #1).
// alpha = max(alpha, 1/h): the exact running mean while 1/h >= alpha, then an EMA (§4.1).
// Non-finite inputs never reach the history (counted in `stats`).
#extension GL_GOOGLE_include_directive : require
#include "svgf/svgf_common.glsl"
#include "common/camera.glsl"
#define VISUAL_POLAR_PARAMS
#include "common/visual_polar.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;     // demodulated radiance, a = samples (0 = untraced)
uniform sampler2D position;  // world position, w > 0 on a hit
uniform sampler2D normal;
uniform sampler2D depth;
uniform sampler2D motion;  // previous pixel - current pixel (optional)
layout(rgba32f) uniform readonly image2D prev_hist_color;
layout(rg32f) uniform readonly image2D prev_hist_moments;
layout(r32f) uniform readonly image2D prev_hist_length;
layout(rgba32f) uniform readonly image2D prev_hist_position;
layout(rgba16f) uniform readonly image2D prev_hist_normal;
layout(rgba32f) uniform writeonly image2D hist_color;  // written here only with feedbackTap 0
layout(rg32f) uniform writeonly image2D hist_moments;
layout(r32f) uniform writeonly image2D hist_length;
layout(rgba32f) uniform writeonly image2D hist_position;
layout(rgba16f) uniform writeonly image2D hist_normal;
layout(rgba32f) uniform writeonly image2D accumulated;  // rgb C, a = h
layout(std430) buffer Stats { uint counters[5]; } stats;

layout(push_constant) uniform Params {
    ivec2 size;
    int history;    // 0: no previous frame (first frame, reset, camera cut, resize)
    int useMotion;  // 1: motion input, 0: world position through the previous camera
    int writeColorHistory;  // feedbackTap 0: the unfiltered accumulation is the colour history
    float alpha;
    float momentsAlpha;
    float maxHistory;
    float positionThreshold;  // relative to the pixel's view depth
    float normalThreshold;    // minimum cosine
    int useVp;  // 1: a Visual-Polar image (the `vp` block): VP history taps and 3x3 fallback
} pc;

// Tap test (disocclusion, §4.1): inside, held data, same surface.
bool tapValid(ivec2 t, vec3 w, vec3 n, float limit2) {
    if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, pc.size))) return false;
    vec4 pw = imageLoad(prev_hist_position, t);
    if (!(pw.w > 0.0)) return false;  // no surface there last frame
    if (!(imageLoad(prev_hist_length, t).x > 0.0)) return false;  // never held a sample
    vec3 d = pw.xyz - w;
    if (!(dot(d, d) <= limit2)) return false;
    return dot(imageLoad(prev_hist_normal, t).xyz, n) >= pc.normalThreshold;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;

    vec4 c = texelFetch(color, p, 0);
    vec4 w = texelFetch(position, p, 0);
    vec3 n = texelFetch(normal, p, 0).xyz;
    float zRaw = texelFetch(depth, p, 0).x;
    bool geometryFinite = svgfFinite4(w) && svgfFinite3(n) && svgfFinite(zRaw);
    if (!geometryFinite) atomicAdd(stats.counters[SVGF_STAT_NONFINITE_GEOMETRY], 1u);
    float z = svgfDepthAt(depth, p);
    bool hit = geometryFinite && w.w > 0.0 && z > 0.0;

    bool sampled = !(c.a <= 0.0);  // a NaN alpha counts as sampled and is caught below
    if (sampled && !svgfFinite4(c)) {
        atomicAdd(stats.counters[SVGF_STAT_NONFINITE_COLOR], 1u);
        sampled = false;  // dropped: the pixel keeps its history
    }
    // Radiance is non-negative; the clamp keeps l^2 finite (svgf_common.glsl).
    vec3 x = sampled ? clamp(c.rgb, vec3(0.0), vec3(SVGF_MAX_SAMPLE)) : vec3(0.0);

    vec3 histC = vec3(0.0);
    vec2 histM = vec2(0.0);
    float histH = 0.0;
    bool valid = false;
    if (hit && pc.history != 0) {
        vec2 prev = vec2(-1.0);
        vec2 mv = vec2(0.0);
        bool ok;
        if (pc.useMotion != 0) {
            vec2 m = texelFetch(motion, p, 0).xy;
            ok = svgfFinite(m.x) && svgfFinite(m.y);
            if (!ok) atomicAdd(stats.counters[SVGF_STAT_NONFINITE_GEOMETRY], 1u);
            mv = ok ? m : vec2(0.0);
            prev = vec2(p) + 0.5 + mv;
        } else {
            ok = cameraPreviousPixel(cameraEyeOf(uint(p.x)), w.xyz, prev);
        }
        // Visual-Polar (seed 003 P5 §3.3): motion rows are rows of this texel's column; the taps
        // sit at each column's own phi height, wrapped on phi (visual_polar.glsl).
        VisualPolarMap vm;
        int x0 = 0;
        if (pc.useVp != 0) {
            uint eye = vpEyeOfColumn(float(p.x));
            vm = vpMapOfEye(eye);
            x0 = int(eye * vm.width);
            prev = vpMovedPosition(vm, p - ivec2(x0, 0), mv);  // eye-local (x, t)
        }
        if (ok) {
            ivec2 taps[4];
            float weights[4];
            // Clamping keeps floor() of a huge value well defined; such taps fail the bounds test.
            vec2 q = clamp(prev - 0.5, vec2(-4.0), vec2(pc.size) + 4.0);
            if (pc.useVp != 0) {
                vpBilinearTaps(vpPrevious(vm), prev, taps, weights);  // previous heights
                for (int i = 0; i < 4; ++i) taps[i].x += x0;
            } else {
                ivec2 base = ivec2(floor(q));
                vec2 f = clamp(q - vec2(base), 0.0, 1.0);
                for (int i = 0; i < 4; ++i) {
                    ivec2 o = ivec2(i & 1, i >> 1);
                    taps[i] = base + o;
                    weights[i] = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
                }
            }
            float limit = pc.positionThreshold * z;
            float limit2 = limit * limit;
            float wsum = 0.0;
            for (int i = 0; i < 4; ++i) {
                ivec2 t = taps[i];
                if (!tapValid(t, w.xyz, n, limit2)) continue;
                float bw = weights[i];
                histC += bw * imageLoad(prev_hist_color, t).rgb;
                histM += bw * imageLoad(prev_hist_moments, t).xy;
                histH += bw * imageLoad(prev_hist_length, t).x;
                wsum += bw;
            }
            if (wsum >= 0.01) {
                valid = true;
                histC /= wsum;  // wsum >= 0.01
                histM /= wsum;
                histH /= wsum;
            } else {
                // Fallback (specs §1 F3): mean of the valid taps of the 3x3 around the pixel.
                histC = vec3(0.0);
                histM = vec2(0.0);
                histH = 0.0;
                float count = 0.0;
                ivec2 centre = ivec2(floor(q + 0.5));  // the pixel holding prev (q is clamped)
                if (pc.useVp != 0) {
                    // The texel holding prev in its own column (x clamped on rho, t wrapped).
                    int c = clamp(int(floor(prev.x)), 0, int(vm.width) - 1);
                    float rows = float(vpRows(vpPrevious(vm), uint(c)));  // >= 1
                    centre = ivec2(c, min(int(fract(prev.y) * rows), int(rows) - 1));
                }
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        ivec2 t = centre + ivec2(dx, dy);
                        if (pc.useVp != 0)
                            t = vpNeighbour(vpPrevious(vm), centre, ivec2(dx, dy)) + ivec2(x0, 0);
                        if (!tapValid(t, w.xyz, n, limit2)) continue;
                        histC += imageLoad(prev_hist_color, t).rgb;
                        histM += imageLoad(prev_hist_moments, t).xy;
                        histH += imageLoad(prev_hist_length, t).x;
                        count += 1.0;
                    }
                if (count > 0.0) {
                    valid = true;
                    histC /= count;
                    histM /= count;
                    histH /= count;
                }
            }
        }
        if (!valid) atomicAdd(stats.counters[SVGF_STAT_REJECTED], 1u);
    }
    // Belt and braces: a history only ever holds finite values, but a reprojected blend of them
    // could still overflow.
    if (valid && !(svgfFinite3(histC) && svgfFinite(histM.x) && svgfFinite(histM.y) &&
                   svgfFinite(histH))) {
        valid = false;
    }

    vec3 C;
    vec2 M;
    float h;
    float l = luminance(x);
    if (valid) {
        if (sampled) {
            h = min(histH + 1.0, pc.maxHistory);
            float a = max(pc.alpha, 1.0 / h);          // h >= 1
            float am = max(pc.momentsAlpha, 1.0 / h);
            C = mix(histC, x, a);
            M = mix(histM, vec2(l, l * l), am);
        } else {
            C = histC;  // untraced or dropped sample: keep the reprojected history
            M = histM;
            h = histH;
        }
    } else if (sampled) {
        C = x;
        M = vec2(l, l * l);
        h = 1.0;
    } else {
        C = vec3(0.0);
        M = vec2(0.0);
        h = 0.0;  // no data: the filter ignores this pixel as a neighbour
    }
    if (!hit) h = 0.0;  // misses keep no history; the filter passes them through

    imageStore(accumulated, p, vec4(C, h));
    imageStore(hist_moments, p, vec4(M, 0.0, 0.0));
    imageStore(hist_length, p, vec4(h));
    imageStore(hist_position, p, hit ? vec4(w.xyz, 1.0) : vec4(0.0));
    imageStore(hist_normal, p, vec4(hit ? n : vec3(0.0), 0.0));
    if (pc.writeColorHistory != 0) imageStore(hist_color, p, vec4(C, 0.0));
}
