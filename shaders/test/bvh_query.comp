#version 460
// Test shader: closest-hit and occlusion queries for a buffer of rays (tests/graph/BvhTests.cpp).
// hits[i] = (t, triangle as uint bits, barycentric u, v); a miss has triangle kBvhNoHit.
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;

#include "common/bvh.glsl"

struct TestRay {
    vec4 originTMin;
    vec4 directionTMax;
};

layout(std430) readonly buffer Rays {
    TestRay rays[];
} test_rays;
layout(std430) writeonly buffer Hits {
    vec4 hits[];
} test_hits;
layout(std430) writeonly buffer Occlusion {
    uint occluded[];
} test_occlusion;

layout(push_constant) uniform Push {
    uint count;
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    TestRay r = test_rays.rays[i];
    BvhHit hit;
    bvhClosestHit(r.originTMin.xyz, r.directionTMax.xyz, r.originTMin.w, r.directionTMax.w, hit);
    test_hits.hits[i] = vec4(hit.t, uintBitsToFloat(hit.triangle), hit.barycentrics);
    bool occluded =
        bvhOccluded(r.originTMin.xyz, r.directionTMax.xyz, r.originTMin.w, r.directionTMax.w);
    test_occlusion.occluded[i] = occluded ? 1u : 0u;
}
