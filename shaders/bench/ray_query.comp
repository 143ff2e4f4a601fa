#version 460
// Ray-throughput benchmark kernel (tests/bench/RayBench.cpp): the BVH traversal of
// shaders/common/bvh.glsl on a buffer of rays, closest hit or (OCCLUSION=1) any hit, so the same
// rays can be timed here and in Embree on the CPU.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;

#include "common/bvh.glsl"

struct BenchRay {
    vec4 originTMin;
    vec4 directionTMax;
};

layout(std430) readonly buffer Rays {
    BenchRay rays[];
} bench_rays;
layout(std430) writeonly buffer Results {
    vec4 results[];  // closest: (t, triangle bits, u, v); occlusion: x = 1 occluded
} bench_results;

layout(push_constant) uniform Push {
    uint count;
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    BenchRay r = bench_rays.rays[i];
#if OCCLUSION
    bool occluded =
        bvhOccluded(r.originTMin.xyz, r.directionTMax.xyz, r.originTMin.w, r.directionTMax.w);
    bench_results.results[i] = vec4(occluded ? 1.0 : 0.0);
#else
    BvhHit hit;
    bvhClosestHit(r.originTMin.xyz, r.directionTMax.xyz, r.originTMin.w, r.directionTMax.w, hit);
    bench_results.results[i] = vec4(hit.t, uintBitsToFloat(hit.triangle), hit.barycentrics);
#endif
}
