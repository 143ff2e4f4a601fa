#version 460
// PreviewSamples, step 3: the texels that got samples become a sample layout (pixel + count) in
// row-major order. One workgroup: each thread owns a contiguous run of rows, counts their
// sampled texels, a prefix sum over the threads gives each run its first entry, then the runs are
// written - a fixed order without atomics (as SampleList), so the layout is the same every run.
#extension GL_GOOGLE_include_directive : require

#define SAMPLE_LAYOUT_WRITE
#include "../common/sample_layout.glsl"
#include "counts.glsl"

const uint kThreads = 256u;
layout(local_size_x = 256) in;

layout(push_constant) uniform Params { uvec2 size; } pc;

shared uint sCounts[kThreads];
shared uint sMax[kThreads];

void main() {
    uint t = gl_LocalInvocationID.x;
    uint rowsPerThread = (pc.size.y + kThreads - 1u) / kThreads;
    uint first = min(t * rowsPerThread, pc.size.y), last = min(first + rowsPerThread, pc.size.y);
    uint n = 0u, most = 0u;
    for (uint y = first; y < last; ++y)
        for (uint x = 0u; x < pc.size.x; ++x) {
            uint c = counts.texels[y * pc.size.x + x];
            n += c > 0u ? 1u : 0u;
            most = max(most, c);
        }
    sCounts[t] = n;
    sMax[t] = most;
    barrier();
    // Inclusive scan (Hillis-Steele) over the threads' counts, and a max reduction alongside.
    for (uint step = 1u; step < kThreads; step <<= 1u) {
        uint add = t >= step ? sCounts[t - step] : 0u;
        uint m = t >= step ? sMax[t - step] : 0u;
        barrier();
        sCounts[t] += add;
        sMax[t] = max(sMax[t], m);
        barrier();
    }
    uint next = sCounts[t] - n;  // exclusive start of this thread's run
    for (uint y = first; y < last; ++y)
        for (uint x = 0u; x < pc.size.x; ++x) {
            uint c = counts.texels[y * pc.size.x + x];
            if (c == 0u) continue;
            sample_layout.entries[next++] = uvec2(sampleLayoutPack(uvec2(x, y)), c);
        }
    if (t == kThreads - 1u) {
        sample_layout.count = sCounts[t];
        sample_layout.maxSamples = sMax[t];
        sample_layout.pad0 = 0u;
        sample_layout.pad1 = 0u;
    }
}
