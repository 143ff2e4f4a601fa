#version 460
// Test shader: specularAlbedoTerms at given (NoV, roughness) (tests/graph/SpecularAlbedoTests.cpp).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;

#include "common/specular_albedo.glsl"

layout(std430) readonly buffer Queries {
    vec2 queries[];
} test_queries;
layout(std430) writeonly buffer Results {
    vec2 results[];
} test_results;

layout(push_constant) uniform Push {
    uint count;
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    vec2 q = test_queries.queries[i];
    test_results.results[i] = specularAlbedoTerms(q.x, q.y);
}
