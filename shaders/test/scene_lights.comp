#version 460
// Test shader: sceneSampleLight from one point with hashed random numbers, plus the MIS pdf
// sceneEmitterPdf recomputes for the sampled point (tests/graph/BvhTests.cpp).
// out[2i] = (light as uint bits, pdf, sceneEmitterPdf or 0 for delta lights, valid 0/1)
// out[2i+1] = (direction, distance)
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;

#include "common/random.glsl"
#include "common/scene_sample.glsl"

layout(std430) writeonly buffer Samples {
    vec4 samples[];
} test_samples;

layout(push_constant) uniform Push {
    vec4 position;
    uint count;
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    uint h = pcgHash(i);
    vec4 u = vec4(uintToUnitFloat(hashCombine(h, 1u)), uintToUnitFloat(hashCombine(h, 2u)),
                  uintToUnitFloat(hashCombine(h, 3u)), uintToUnitFloat(hashCombine(h, 4u)));
    SceneLightSample s;
    bool valid = sceneSampleLight(pc.position.xyz, u, s);
    float misPdf = 0.0;
    if (valid && !s.isDelta)
        misPdf = sceneEmitterPdf(s.light, pc.position.xyz,
                                 pc.position.xyz + s.direction * s.distance);
    test_samples.samples[2u * i] =
        vec4(uintBitsToFloat(s.light), s.pdf, misPdf, valid ? 1.0 : 0.0);
    test_samples.samples[2u * i + 1u] = vec4(s.direction, s.distance);
}
