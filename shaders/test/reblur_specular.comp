#version 460
// Test shader: the formulas of recurrent_blur/reblur_specular.glsl on a grid of inputs
// (tests/graph/RecurrentBlurSpecularOracleTests.cpp compares them with a double-precision CPU version).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;

#include "recurrent_blur/reblur_specular.glsl"

// Per query, 5 vec4: (n, roughness), (v, parallax), (nov, hitDist, viewDist, roughness2),
// (n2, shrink), (normalizedFrames, worldRadius, -, -).
layout(std430) readonly buffer Queries {
    vec4 q[];
} test_queries;
// Per query, 4 vec4: (dominant direction, lobe half angle), (max frames, hit radius factor,
// roughness weight, normal weight), (T, radius scale), (B, 0).
layout(std430) writeonly buffer Results {
    vec4 r[];
} test_results;

layout(push_constant) uniform Push {
    uint count;
    float maxFrames;
    float basePower;
    float curve;
    float k;
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    vec4 q0 = test_queries.q[5u * i], q1 = test_queries.q[5u * i + 1u];
    vec4 q2 = test_queries.q[5u * i + 2u], q3 = test_queries.q[5u * i + 3u];
    vec4 q4 = test_queries.q[5u * i + 4u];
    float roughness = q0.w;
    vec3 t, b;
    reblurKernelBasis(q0.xyz, q1.xyz, roughness, q4.y, q4.x, t, b);
    test_results.r[4u * i] = vec4(reblurSpecularDominantDirection(q0.xyz, q1.xyz, roughness),
                                  reblurSpecularLobeHalfAngle(roughness));
    test_results.r[4u * i + 1u] =
        vec4(reblurMaxAccumulatedFrames(roughness, q2.x, q1.w, pc.maxFrames, pc.basePower,
                                        pc.curve),
             reblurHitDistanceRadiusFactor(q2.y, q2.z, roughness, pc.k),
             reblurRoughnessWeight(roughness, q2.w), reblurSpecularNormalWeight(q0.xyz, q3.xyz,
                                                                                roughness, q3.w));
    test_results.r[4u * i + 2u] = vec4(t, reblurSpecularRadiusScale(roughness));
    test_results.r[4u * i + 3u] = vec4(b, 0.0);
}
