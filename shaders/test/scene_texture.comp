#version 460
// Test shader: sceneSampleTexture and sceneMaterial at given uvs (tests/unit/BvhTests.cpp).
// query = (u, v, texture index as int bits, srgb 0/1); with MATERIAL_QUERY the third component
// is a material index and the result is (baseColor.rgb, roughness).
#extension GL_GOOGLE_include_directive : require
layout(local_size_x = 64) in;

#include "common/scene_sample.glsl"

layout(std430) readonly buffer Queries {
    vec4 queries[];
} test_queries;
layout(std430) writeonly buffer Results {
    vec4 results[];
} test_results;

layout(push_constant) uniform Push {
    uint count;
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    vec4 q = test_queries.queries[i];
#ifdef MATERIAL_QUERY
    SceneMaterialSample m = sceneMaterial(floatBitsToUint(q.z), q.xy);
    test_results.results[i] = vec4(m.baseColor, m.roughness);
#else
    test_results.results[i] = sceneSampleTexture(floatBitsToInt(q.z), q.xy, q.w != 0.0);
#endif
}
