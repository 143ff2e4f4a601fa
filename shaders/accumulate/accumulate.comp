#version 460
// Accumulate: per-pixel running mean over frames (the reference-render building block).
// Welford's update mean_n = mean_{n-1} + (x - mean_{n-1}) / n stays accurate for long runs,
// unlike a float sum divided at the end.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;
layout(rgba32f) uniform image2D mean;
layout(r32f) uniform image2D count;

layout(push_constant) uniform Params {
    ivec2 size;
    int restart;      // 1 on the first frame after a reset: forget the previous mean
    int alphaWeight;  // 1: x.a samples stand behind x.rgb (seed 003 P4 §3, scattered samples)
} pc;

bool finite4(vec4 v) { return !any(isnan(v)) && !any(isinf(v)); }

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    vec4 x = texelFetch(color, p, 0);
    float n = pc.restart != 0 ? 0.0 : imageLoad(count, p).r;
    vec4 m = pc.restart != 0 ? vec4(0.0) : imageLoad(mean, p);
    // A NaN/Inf sample is dropped for this pixel only: it never enters the running mean.
    if (pc.alphaWeight != 0) {
        // Weighted Welford: n' = n + w, m' = m + (x - m) w / n' (the mean of all samples, as
        // sum / count would give). w <= 0 (an untraced texel) or non-finite changes nothing.
        float w = x.a;
        if (finite4(x) && w > 0.0) {
            n += w;
            m.rgb += (x.rgb - m.rgb) * (w / n);  // n >= w > 0
        }
        m.a = n > 0.0 ? 1.0 : 0.0;  // coverage: 0 = never sampled (P4 leaves such texels empty)
    } else if (finite4(x)) {
        n += 1.0;
        m += (x - m) / n;  // n >= 1 here
    }
    imageStore(mean, p, m);
    imageStore(count, p, vec4(n));
}
