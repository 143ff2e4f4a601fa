#version 460
// SampleList: writes a sample layout (shaders/common/sample_layout.glsl) listing the pixels a
// simple pattern selects, in row-major order. One workgroup: each thread owns a contiguous run
// of pixels, counts its selections, a prefix sum over the threads gives every run its first
// entry, then the runs are written. The order is therefore fixed (deterministic) without atomics;
// the selection rule mirrors core/scene/SampleLayout.cpp (samplePatternSelects) bit for bit.
#extension GL_GOOGLE_include_directive : require

#define SAMPLE_LAYOUT_WRITE
#include "../common/sample_layout.glsl"
#include "../common/random.glsl"

const uint kThreads = 256u;
layout(local_size_x = 256) in;

layout(push_constant) uniform Params {
    uvec2 size;       // image (whole side-by-side image), each >= 1
    uint pattern;     // 0 all, 1 checkerboard, 2 every_nth, 3 random
    uint n;           // every_nth, >= 1
    uint threshold;   // random: selected when hash < threshold; 0xFFFFFFFF = all
    uint seed;        // random
    uint samples;     // per entry, >= 1
} pc;

shared uint sCounts[kThreads];

bool selects(uint index) {
    uint x = index % pc.size.x;  // size.x >= 1 (the pass checks)
    uint y = index / pc.size.x;
    if (pc.pattern == 1u) return ((x + y) & 1u) == 0u;
    if (pc.pattern == 2u) return index % max(pc.n, 1u) == 0u;
    if (pc.pattern == 3u)
        return pc.threshold == 0xFFFFFFFFu || hashCombine(pc.seed, index) < pc.threshold;
    return true;
}

void main() {
    uint t = gl_LocalInvocationID.x;
    uint pixels = pc.size.x * pc.size.y;
    uint chunk = (pixels + kThreads - 1u) / kThreads;
    uint begin = min(t * chunk, pixels);
    uint end = min(begin + chunk, pixels);

    uint mine = 0u;
    for (uint i = begin; i < end; ++i)
        if (selects(i)) ++mine;
    sCounts[t] = mine;
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
        sample_layout.maxSamples = total > 0u ? pc.samples : 0u;
        sample_layout.pad0 = 0u;
        sample_layout.pad1 = 0u;
    }
    barrier();

    uint capacity = uint(sample_layout.entries.length());
    uint out_ = sCounts[t];
    for (uint i = begin; i < end; ++i) {
        if (!selects(i)) continue;
        if (out_ < capacity)
            sample_layout.entries[out_] =
                uvec2(sampleLayoutPack(uvec2(i % pc.size.x, i / pc.size.x)), pc.samples);
        ++out_;
    }
}
