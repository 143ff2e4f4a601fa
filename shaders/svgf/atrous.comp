#version 460
// One SVGF a-trous level (Schied et al. 2017 §4.3-4.4; specs §1 step 4): 5x5 taps at step
// 2^level with the B3-spline kernel h = (1/16, 1/4, 3/8, 1/4, 1/16), weighted by depth (screen-
// space gradient), normal and variance-guided luminance edge-stopping functions (Eq. 3-5). The
// luminance term divides by sigma_l times a standard deviation (§4.4, Eq. 5): the paper takes the
// centre's (3x3 Gaussian prefilter of its variance); we take the larger of that and the tap's
// variance, so that w(p, q) = w(q, p). With the centre's alone a zero-variance dark pixel rejects
// its bright neighbours while a bright (high-variance) pixel accepts its dark ones: energy flows
// one way and heavy-tailed noise loses its mean (the forest lost 20-28 %, issue 12). On a
// homogeneous region both variances agree and sigma_l keeps the paper's calibration. Variance is propagated as sum(w^2 var) / (sum w)^2. Misses pass through
// and weigh 0 as neighbours, as do pixels without data (h = 0, e.g. never-traced foveated
// periphery), which this way are filled from their neighbours. The level `feedbackTap` also
// writes the colour history (§4.1: the first level's output); the last level remodulates.
#extension GL_GOOGLE_include_directive : require
#define VISUAL_POLAR_PARAMS
#include "common/visual_polar.glsl"
#include "svgf/svgf_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D normal;
uniform sampler2D depth;
uniform sampler2D albedo;    // optional (open: 1)
uniform sampler2D emission;  // optional (open: 0)
layout(rgba32f) uniform readonly image2D accumulated;  // a = h (which pixels hold data)
layout(rgba32f) uniform readonly image2D atrous_in;    // rgb C, a = variance
layout(rgba32f) uniform writeonly image2D atrous_out;
layout(rgba32f) uniform writeonly image2D hist_color;
layout(rgba32f) uniform writeonly image2D illumination;
layout(rgba32f) uniform writeonly image2D filtered;

layout(push_constant) uniform Params {
    ivec2 size;
    int stepSize;  // 2^level
    int writeColorHistory;
    int last;  // 1: also write illumination and filtered
    int useAlbedo;
    int useEmission;
    float sigmaLuminance;
    float sigmaNormal;
    float sigmaDepth;
    int useVp;  // 1: a Visual-Polar image: taps through vpNeighbour (phi wrapped, per-column
                // heights; P5 §3.3)
} pc;

const float kB3[3] = float[3](3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);  // indexed by |offset|

// 3x3 Gaussian of the variance (weights 1/4, 1/8, 1/16), reads clamped to the image.
float prefilteredVariance(ivec2 p) {
    float v = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            float k = (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
            v += k * imageLoad(atrous_in, svgfClamp(p + ivec2(dx, dy), pc.size)).a;
        }
    return max(v, 0.0);  // variances are >= 0; the clamp guards the sqrt below
}

// The tap at offset `off` from texel p: screen addressing, or on a Visual-Polar image the
// neighbour wrapped on phi at the target column's own height (visual_polar.glsl).
ivec2 svgfTap(ivec2 p, ivec2 off) {
    return pc.useVp == 0 ? p + off : vpImageNeighbour(p, off);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;

    vec4 centre = imageLoad(atrous_in, p);
    float zp = svgfDepthAt(depth, p);
    vec3 np = svgfNormalAt(normal, p);
    vec4 result = centre;
    if (zp > 0.0) {
        vec2 grad = svgfDepthGradient(depth, p, pc.size, zp, pc.useVp != 0);
        float lp = luminance(centre.rgb);
        float varP = prefilteredVariance(p);  // >= 0
        float wc = imageLoad(accumulated, p).a > 0.0 ? kB3[0] * kB3[0] : 0.0;
        vec3 sumC = wc * centre.rgb;
        float sumV = wc * wc * centre.a;
        float sumW = wc;
        for (int dy = -2; dy <= 2; ++dy)
            for (int dx = -2; dx <= 2; ++dx) {
                if (dx == 0 && dy == 0) continue;
                ivec2 off = pc.stepSize * ivec2(dx, dy);
                ivec2 q = svgfTap(p, off);
                if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, pc.size))) continue;
                float zq = svgfDepthAt(depth, q);
                if (zq <= 0.0 || !(imageLoad(accumulated, q).a > 0.0)) continue;
                vec4 cq = imageLoad(atrous_in, q);
                // Symmetric noise level (see the header). sigma_l > 0 (parameter range), the
                // variances are >= 0 (clamped where made), 1e-10 keeps the division finite.
                float lumDen = pc.sigmaLuminance * sqrt(max(varP, max(cq.a, 0.0))) + 1e-10;
                float wgt = kB3[abs(dx)] * kB3[abs(dy)] *
                            svgfDepthWeight(zp, zq, grad, vec2(off), pc.sigmaDepth) *
                            svgfNormalWeight(np, svgfNormalAt(normal, q), pc.sigmaNormal) *
                            exp(-abs(lp - luminance(cq.rgb)) / lumDen);
                sumC += wgt * cq.rgb;
                sumV += wgt * wgt * cq.a;
                sumW += wgt;
            }
        // sumW == 0 only for a pixel without data whose neighbours hold none either: keep it.
        if (sumW > 0.0) result = vec4(sumC / sumW, sumV / (sumW * sumW));
    }
    result = sanitize(result);
    imageStore(atrous_out, p, result);
    if (pc.writeColorHistory != 0) imageStore(hist_color, p, vec4(result.rgb, 0.0));
    if (pc.last != 0) {
        imageStore(illumination, p, result);
        // Remodulation (as PathTrace demodulated): albedo' = albedo where > 1e-3, else 1.
        vec3 a = vec3(1.0);
        if (pc.useAlbedo != 0) {
            vec3 t = texelFetch(albedo, p, 0).rgb;
            if (svgfFinite3(t)) a = mix(vec3(1.0), t, greaterThan(t, vec3(1e-3)));
        }
        vec3 le = vec3(0.0);
        if (pc.useEmission != 0) {
            vec3 t = texelFetch(emission, p, 0).rgb;
            if (svgfFinite3(t)) le = t;
        }
        imageStore(filtered, p, sanitize(vec4(result.rgb * a + le, 1.0)));
    }
}
