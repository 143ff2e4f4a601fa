#version 460
// FoveationMask: seed 000's three-layer foveated distribution (Peres et al. 2023, §3.2, §4.1,
// Table 1) around each eye's gaze point (camera_info.eyes[e].gaze), written as a sample layout
// (shaders/common/sample_layout.glsl) and as the mask image (B of Eq. 2 + layer id + spp).
//
// One workgroup, as in SampleList: each thread owns a contiguous row-major run of pixels of the
// whole side-by-side image, evaluates them (writing the mask) and counts its sampled pixels; a
// prefix sum over the threads gives every run its first entry; then the runs are written. The
// entry order is fixed (deterministic) without atomics. The evaluation runs twice per pixel
// (count, then write): a hash and a distance, cheap next to storing the count per pixel. The
// pass is cached, so this runs once per gaze / parameter change.
#extension GL_GOOGLE_include_directive : require

#define SAMPLE_LAYOUT_WRITE
#include "../common/sample_layout.glsl"
#include "../common/random.glsl"
#include "../common/camera.glsl"

const uint kThreads = 256u;
layout(local_size_x = 256) in;

layout(r32ui) uniform writeonly uimage2D mask;

layout(push_constant) uniform Params {
    uvec2 size;              // whole side-by-side image, each >= 1
    vec2 radii;              // r0 <= r1 (the pass checks), in pixels or degrees
    uint unitDegrees;        // 1: radii are eccentricities in degrees
    float outerProbability;  // [0, 1]
    uint seed;
    uint sppFovea;
    uint sppMiddle;
    uint sppOuter;
} pc;

shared uint sCounts[kThreads];
shared uint sMaxSamples;

// View-space direction (unnormalized, z = -1) through a point of an eye image, exactly as
// cameraRay builds it (camera.glsl): tan(yfov/2) = jitter.z, eye aspect = jitter.w.
vec3 viewDirection(vec2 local) {
    vec2 eyeSize = vec2(max(camera_info.size.xy, uvec2(1u)));
    vec2 ndc = vec2(2.0 * local.x / eyeSize.x - 1.0, 1.0 - 2.0 * local.y / eyeSize.y);
    float t = camera_info.jitter.z;
    return vec3(ndc.x * t * camera_info.jitter.w, ndc.y * t, -1.0);
}

// Distance of pixel `p` (whole-image coordinates) from its eye's gaze point: pixels, or the
// eccentricity angle in degrees (unitDegrees).
float gazeDistance(uvec2 p) {
    uint eye = cameraEyeOf(p.x);
    vec2 local = vec2(p) + 0.5 - vec2(camera_info.eyes[eye].position.w, 0.0);
    vec2 gaze = camera_info.eyes[eye].gaze.xy * vec2(camera_info.size.xy);
    if (pc.unitDegrees == 0u) return length(local - gaze);
    vec3 a = viewDirection(local), b = viewDirection(gaze);
    // atan(|a x b|, a . b) is accurate for small angles (acos is not); a . b >= 1 (z = -1 each).
    return degrees(atan(length(cross(a, b)), dot(a, b)));
}

// 0 fovea (d <= r0), 1 middle (r0 < d <= r1), 2 outer. Seed 000 §3.2: the middle layer starts at
// r0 + 1 and the outer at r1 + 1 for integer pixel distances; with real distances, "beyond r".
uint layerOf(float d) { return d <= pc.radii.x ? 0u : (d <= pc.radii.y ? 1u : 2u); }

// Sampling probability: 1 in the fovea, linear from 1 at r0 to outerProbability at r1 (seed 000
// §3.2 after Weier et al.), outerProbability beyond.
float probability(float d, uint layer) {
    if (layer == 0u) return 1.0;
    if (layer == 2u) return pc.outerProbability;
    // layer 1 implies r0 < d <= r1, so r1 - r0 > 0; the max only guards float rounding.
    float t = clamp((d - pc.radii.x) / max(pc.radii.y - pc.radii.x, 1e-20), 0.0, 1.0);
    return mix(1.0, pc.outerProbability, t);
}

// The mask word of pixel `index`: bit 0 sampled, bits 1-2 layer, bits 16-31 samples.
uint evaluate(uint index) {
    uvec2 p = uvec2(index % pc.size.x, index / pc.size.x);  // size.x >= 1 (the pass clamps)
    float d = gazeDistance(p);
    uint layer = layerOf(d);
    // A uniform in [0, 1) (24 bits) per pixel from the seed: p = 1 always samples, p = 0 never.
    bool sampled = uintToUnitFloat(hashCombine(pc.seed, index)) < probability(d, layer);
    uint spp = layer == 0u ? pc.sppFovea : (layer == 1u ? pc.sppMiddle : pc.sppOuter);
    return sampled ? (1u | (layer << 1) | (spp << 16)) : (layer << 1);
}

void main() {
    uint t = gl_LocalInvocationID.x;
    uint pixels = pc.size.x * pc.size.y;
    uint chunk = (pixels + kThreads - 1u) / kThreads;
    uint begin = min(t * chunk, pixels);
    uint end = min(begin + chunk, pixels);
    if (t == 0u) sMaxSamples = 0u;
    barrier();

    uint mine = 0u, maxSamples = 0u;
    for (uint i = begin; i < end; ++i) {
        uint m = evaluate(i);
        imageStore(mask, ivec2(i % pc.size.x, i / pc.size.x), uvec4(m));
        if ((m & 1u) != 0u) {
            ++mine;
            maxSamples = max(maxSamples, m >> 16);
        }
    }
    sCounts[t] = mine;
    atomicMax(sMaxSamples, maxSamples);
    barrier();
    // Exclusive prefix sum by one thread: 256 additions, negligible next to the pixel loops.
    if (t == 0u) {
        uint sum = 0u;
        for (uint i = 0u; i < kThreads; ++i) {
            uint c = sCounts[i];
            sCounts[i] = sum;
            sum += c;
        }
        uint capacity = uint(sample_layout.entries.length());
        uint total = min(sum, capacity);
        sample_layout.count = total;
        sample_layout.maxSamples = total > 0u ? sMaxSamples : 0u;
        sample_layout.pad0 = 0u;
        sample_layout.pad1 = 0u;
    }
    barrier();

    uint capacity = uint(sample_layout.entries.length());
    uint out_ = sCounts[t];
    for (uint i = begin; i < end; ++i) {
        uint m = evaluate(i);
        if ((m & 1u) == 0u) continue;
        if (out_ < capacity)
            sample_layout.entries[out_] =
                uvec2(sampleLayoutPack(uvec2(i % pc.size.x, i / pc.size.x)), m >> 16);
        ++out_;
    }
}
