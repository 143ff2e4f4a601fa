#version 460
// Test shader: sceneSampleTexture and sceneMaterial at given uvs (tests/graph/SceneGpuTests.cpp).
// query = (u, v, texture index as int bits, srgb 0/1); with MATERIAL_QUERY the third component
// is a material index and the result is (baseColor.rgb, roughness); with VIEW_QUERY it is a
// material index, the fourth a texture slot, and the result that slot's texture read through its
// view (KHR_texture_transform + sampler), sRGB except for metallic-roughness.
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
#if defined(MATERIAL_QUERY)
    SceneMaterialSample m = sceneMaterial(floatBitsToUint(q.z), q.xy);
    test_results.results[i] = vec4(m.baseColor, m.roughness);
#elif defined(VIEW_QUERY)
    uint material = floatBitsToUint(q.z);
    uint slot = uint(q.w);
    ivec4 t = scene_materials.materials[material].textures;
    int texture = slot == 0u ? t.x : (slot == 1u ? t.y : t.z);
    test_results.results[i] = sceneSampleMaterialTexture(material, slot, texture, q.xy, slot != 1u);
#else
    test_results.results[i] = sceneSampleTexture(floatBitsToInt(q.z), q.xy, q.w != 0.0);
#endif
}
