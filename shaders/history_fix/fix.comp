#version 460
// HistoryFix (seed 004, the ReBLUR talk; specs §2 HistoryFix): a pixel with few accumulated
// frames (N < historyFixFrames, e.g. just disoccluded) is rebuilt from coarser data, a pixel with
// enough history is copied bit-exactly ("no disocclusion = no work").
//   method 0 (mips, the talk): level L = ceil(4 (1 - N / Nhf)) -> 4, 3, 2 over the first three
//     frames (the talk's "frame 0 mip 4, frame 1 mip 3, frame 2 mip 2"), upsampled bilinearly
//     with depth-aware weights [z_L > 0] * saturate(1 - |z_L - z| / (0.05 z)) (the talk names
//     UPSAMPLING_VIEWZ_SENSITIVITY without a value; 0.05 is ours). No weight: the next finer level.
//   Both sizes are for referenceHeight rows (1080): at H rows the level shifts by
//   round(log2(H / referenceHeight)) and the stride scales by H / referenceHeight.
//   method 1 (stride, NRD v4.14): 5x5 taps without centre and corners at a stride of
//     floor(basePixelStride / (2 + N)) px, weight (1 + N_q) x the same depth weight; the sum starts
//     with the pixel itself at weight 1 + N.
// The count is color.a or, when connected, count.a (BMFR: filtered colour, accumulated count).
// With `albedo` / `emission` connected both methods rebuild the demodulated colour and remodulate
// it with the pixel's own albedo' and emission (mip_common.glsl). With `normal` connected a coarse
// texel or stride tap whose normal deviates by more than normalAngle is not used (its weight falls
// to 0 at the angle), so the rebuild does not cross a crease of equal depth. Alpha passes through.
#extension GL_GOOGLE_include_directive : require
#include "common/color.glsl"
#include "history_fix/mip_common.glsl"

// HF_PASS_THROUGH = 1 (historyFixFrames = 0): only the copy. With a runtime "nothing to rebuild"
// the pass cost as much as a rebuild on lavapipe (8.5 vs 9.0 ms at 256x256, issue 13).
#ifndef HF_PASS_THROUGH
#define HF_PASS_THROUGH 0
#endif

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;
uniform sampler2D depth;
uniform sampler2D count;  // optional: the frame count is its alpha (else color.a)
uniform sampler2D albedo;    // optional (useAlbedo)
uniform sampler2D emission;  // optional (useEmission)
uniform sampler2D normal;    // optional (useNormal)
uniform sampler2D roughness;  // optional (useRoughness): r = linear roughness
uniform sampler2D mip1;
uniform sampler2D mip2;
uniform sampler2D mip3;
uniform sampler2D mip4;
uniform sampler2D nmip1;  // mean normals of the levels (useNormal)
uniform sampler2D nmip2;
uniform sampler2D nmip3;
uniform sampler2D nmip4;
layout(rgba32f) uniform writeonly image2D result;

layout(push_constant) uniform Params {
    ivec2 size;
    int eyeWidth;
    int eyes;
    ivec4 blocks;        // blocks per eye of levels 1..4
    ivec4 heights;       // rows of levels 1..4
    float fixFrames;     // Nhf: pixels with N < Nhf are rebuilt
    float countOffset;   // N = alpha - countOffset (1 for a sample count such as BMFR's)
    int method;          // 0 mips, 1 stride
    float baseStride;    // px (stride method)
    float depthSensitivity;
    int useCount;        // 1: N from count.a, else from color.a
    int levelShift;      // round(log2(H / referenceHeight)), <= 0 below the reference height
    int useAlbedo;       // 1: demodulate by albedo' before averaging, remodulate after
    int useEmission;     // 1: subtract emission before averaging, add it back after
    int useNormal;       // 1: normal test against the texel's / tap's normal
    float cosNormal;     // cos(normalAngle)
    int clampToNeighbours;  // 1: the rebuilt value is clamped to the pixel's 3x3 range
    int useRoughness;    // 1: specular level x roughness (seed 004 "Hierarchical history
                         // reconstruction": mipLevel = 4 (1 - N / Nhf) roughness)
} pc;

bool demodulating() { return pc.useAlbedo != 0 || pc.useEmission != 0; }

vec3 albedoAt(ivec2 q) { return hfSafeAlbedo(texelFetch(albedo, q, 0).rgb, pc.useAlbedo != 0); }

vec3 emissionAt(ivec2 q) {
    return hfSafeEmission(texelFetch(emission, q, 0).rgb, pc.useEmission != 0);
}

// The value the rebuild averages: the colour itself, or (c - emission) / albedo' (albedo' >= 1e-3).
vec3 demodulated(ivec2 q, vec3 c) {
    return demodulating() ? (c - emissionAt(q)) / albedoAt(q) : c;
}

float countAt(ivec2 q, vec4 c) {
    float a = pc.useCount != 0 ? texelFetch(count, q, 0).a : c.a;
    return a - pc.countOffset;
}

float depthWeight(float zq, float z) {  // z > 0 (caller)
    return zq > 0.0 ? clamp(1.0 - abs(zq - z) / (pc.depthSensitivity * z), 0.0, 1.0) : 0.0;
}

vec3 normalMipFetch(int level, ivec2 t) {
    if (level == 1) return texelFetch(nmip1, t, 0).xyz;
    if (level == 2) return texelFetch(nmip2, t, 0).xyz;
    if (level == 3) return texelFetch(nmip3, t, 0).xyz;
    return texelFetch(nmip4, t, 0).xyz;
}

vec4 mipFetch(int level, ivec2 t) {
    if (level == 1) return texelFetch(mip1, t, 0);
    if (level == 2) return texelFetch(mip2, t, 0);
    if (level == 3) return texelFetch(mip3, t, 0);
    return texelFetch(mip4, t, 0);
}

// Depth-aware bilinear upsample of `level` at pixel p of eye `eye` (local column xl).
bool upsample(int level, int eye, int xl, int y, float z, vec3 n, out vec3 value) {
    int blocks = pc.blocks[level - 1], rows = pc.heights[level - 1];
    float scale = float(1 << level);
    vec2 f = (vec2(xl, y) + 0.5) / scale - 0.5;
    ivec2 i0 = ivec2(floor(f));
    vec2 t = f - vec2(i0);
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 q = clamp(i0 + o, ivec2(0), ivec2(blocks - 1, rows - 1));  // inside the eye
        ivec2 texel = ivec2(eye * blocks + q.x, q.y);
        vec4 m = mipFetch(level, texel);
        float w = (o.x == 1 ? t.x : 1.0 - t.x) * (o.y == 1 ? t.y : 1.0 - t.y) * depthWeight(m.a, z);
        if (pc.useNormal != 0 && w > 0.0)
            w *= hfNormalWeight(n, normalMipFetch(level, texel), pc.cosNormal);
        if (!(w > 0.0)) continue;
        sum += w * m.rgb;
        wsum += w;
    }
    if (!(wsum > 1e-6)) return false;
    value = sum / wsum;
    return true;
}

// Range of the averaged (possibly demodulated) colour over the pixel's 3x3 neighbours with a
// surface, inside its eye (ours, issue 13). Where the input is already clean (a delta sun on a
// normal-mapped, textured surface: FlightHelmet) the range is tight and keeps the pixel's own
// detail; where it is noisy (1 spp under an area light) it is wide and the rebuild passes.
void neighbourRange(ivec2 p, int x0, int x1, out vec3 lo, out vec3 hi) {
    lo = vec3(3.0e38);
    hi = vec3(-3.0e38);
    for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) {
            ivec2 q = p + ivec2(i, j);
            if (q.x < x0 || q.x > x1 || q.y < 0 || q.y >= pc.size.y) continue;
            float zq = texelFetch(depth, q, 0).r;
            if (!(zq > 0.0) || isinf(zq)) continue;  // sky: its colour is not the surface's
            vec3 v = demodulated(q, sanitize(texelFetch(color, q, 0)).rgb);
            lo = min(lo, v);
            hi = max(hi, v);
        }
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    vec4 c = texelFetch(color, p, 0);
    float n = countAt(p, c);
    float z = texelFetch(depth, p, 0).r;
#if HF_PASS_THROUGH
    imageStore(result, p, sanitize(c));
    return;
#endif
    // Enough history, or no surface: untouched (bit-exact for finite values; NaN/Inf -> 0 so a
    // bad value never leaves this pass).
    if (!(n < pc.fixFrames) || !(z > 0.0) || isinf(z)) {
        imageStore(result, p, sanitize(c));
        return;
    }
    n = max(n, 0.0);
    int eye = eyeOfPixel(p.x, pc.eyeWidth, pc.eyes);
    int x0 = eye * pc.eyeWidth;
    int x1 = eye == pc.eyes - 1 ? pc.size.x - 1 : x0 + pc.eyeWidth - 1;
    vec3 nrm = pc.useNormal != 0 ? texelFetch(normal, p, 0).xyz : vec3(0.0);
    // The pixel's own value in the averaged (possibly demodulated) space; remodulated at the end.
    vec3 fixedColor = demodulated(p, sanitize(c).rgb);
    if (pc.method == 0) {
        // The talk's level, shifted to this resolution; <= 0: finer than a 2x2 block, nothing to
        // rebuild from (the loop does not run and the pixel keeps its value).
        // Specular (roughness connected): the talk's level x roughness, so a mirror (0) keeps
        // its own sharp value and a rough lobe is rebuilt like a diffuse one.
        float rough = pc.useRoughness != 0
                          ? clamp(sanitize(texelFetch(roughness, p, 0)).r, 0.0, 1.0)
                          : 1.0;
        int level =
            min(int(ceil(4.0 * (1.0 - n / pc.fixFrames) * rough)) + pc.levelShift, 4);  // Nhf > 0
        bool rebuilt = false;
        for (int l = level; l >= 1 && !rebuilt; --l) {
            vec3 v;
            rebuilt = upsample(l, eye, p.x - x0, p.y, z, nrm, v);
            if (rebuilt) fixedColor = v;
        }
        if (!rebuilt) {  // kept as it came (no remodulation round trip)
            imageStore(result, p, sanitize(c));
            return;
        }
    } else {
        int stride = max(int(floor(pc.baseStride / (2.0 + n))), 1);
        vec3 sum = fixedColor * (1.0 + n);
        float wsum = 1.0 + n;
        for (int j = -2; j <= 2; ++j)
            for (int i = -2; i <= 2; ++i) {
                if ((i == 0 && j == 0) || (abs(i) == 2 && abs(j) == 2)) continue;
                ivec2 q = clamp(p + ivec2(i, j) * stride, ivec2(x0, 0), ivec2(x1, pc.size.y - 1));
                vec4 s = sanitize(texelFetch(color, q, 0));
                float w = depthWeight(texelFetch(depth, q, 0).r, z) *
                          (1.0 + clamp(countAt(q, s), 0.0, 64.0));  // NaN: skipped below
                if (pc.useNormal != 0 && w > 0.0)
                    w *= hfNormalWeight(nrm, texelFetch(normal, q, 0).xyz, pc.cosNormal);
                if (!(w > 0.0)) continue;
                sum += w * demodulated(q, s.rgb);
                wsum += w;
            }
        fixedColor = sum / wsum;  // wsum >= 1
    }
    if (pc.clampToNeighbours != 0) {
        vec3 lo, hi;
        neighbourRange(p, x0, x1, lo, hi);  // p itself has a surface: lo <= hi
        fixedColor = clamp(fixedColor, lo, hi);
    }
    if (demodulating()) fixedColor = fixedColor * albedoAt(p) + emissionAt(p);
    imageStore(result, p, sanitize(vec4(fixedColor, c.a)));
}
