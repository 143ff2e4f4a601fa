// A Scene on the GPU: geometry, BVH, materials, textures and lights in storage buffers with
// fixed names that shaders declare by including shaders/common/scene_data.glsl. Passes call
// bind() on their pipelines and compile with defines() so absent features compile out.
// Layouts and rationale: docs/scene-gpu.md.
#pragma once
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/scene/Bvh.h"
#include "core/scene/LightTable.h"
#include "core/scene/Scene.h"

namespace fovea::gpu {
class Buffer;
class ComputePipeline;
class Context;
}  // namespace fovea::gpu

namespace fovea::scene {

// The std430/std140 element layouts, mirrored field by field in shaders/common/scene_data.glsl.
// vec3 + scalar pairs share one 16-byte slot in both languages; the asserts pin every size.
namespace layout {

struct Vertex {           // scene_vertices
    glm::vec4 positionU;  // xyz position, w = uv.x
    glm::vec4 normalV;    // xyz shading normal, w = uv.y
};
struct Triangle {  // scene_triangles, in Bvh::triangleOrder()
    glm::uvec3 indices;
    uint32_t material;
};
struct TrianglePositions {  // scene_bvh_triangles: what the intersection loop reads
    glm::vec4 v0;           // xyz; w 1 = the material has an alpha test (params.w != 0), else 0
    glm::vec4 e1;           // v1 - v0
    glm::vec4 e2;           // v2 - v0
};
struct Material {         // scene_materials
    glm::vec4 baseColor;  // linear RGBA factor
    glm::vec4 emissive;   // rgb linear factor; w = emitted power per unit area (LightTable)
    glm::vec4 params;     // x metallic, y roughness, z doubleSided (0/1), w alpha threshold:
                          // 0 opaque, > 0 MASK cutoff, -1 BLEND (glTF 2.0 §3.9.4)
    glm::ivec4 textures;  // x baseColor (sRGB), y metallicRoughness (linear), z emissive (sRGB),
                          // w normal (linear, tangent space); -1 = none
};
struct Texture {      // scene_textures
    uint32_t offset;  // first texel in scene_texels
    uint32_t width;   // 0 = no texels (sampling returns 1)
    uint32_t height;
    uint32_t flags;  // reserved
};
// scene_texture_views: kTextureSlots per material (base colour, metallic-roughness, emissive,
// normal: the order of Material::textures), each the slot's TextureView (TextureView.h).
inline constexpr uint32_t kTextureSlots = 4;
inline constexpr uint32_t kTextureViewTransformed = 1u << 5;  // flags bit: apply row0/row1
struct TextureView {
    glm::vec3 row0;  // KHR_texture_transform: u' = dot(row0, (u, v, 1)); zero when identity
    uint32_t flags;  // TextureSampler::flags() | kTextureViewTransformed
    glm::vec3 row1;  // v' = dot(row1, (u, v, 1))
    float scale;     // the normal slot: normalTexture.scale (glTF §3.9.3); 1 elsewhere
};
struct Light {  // scene_lights (punctual)
    glm::vec3 position;
    float range;          // 0 = infinite
    glm::vec3 direction;  // the way the light shines, normalized
    uint32_t type;        // Scene Light::Type
    glm::vec3 intensity;  // color * intensity
    float spotScale;      // KHR_lights_punctual cone attenuation: saturate(cd * scale + offset)^2
    float spotOffset;
    float pad[3];
};
struct Info {  // scene_info (uniform; std140 == std430 for this member order)
    uint32_t vertexCount, triangleCount, nodeCount, materialCount;
    uint32_t textureCount, texelCount, lightCount, emitterCount;
    uint32_t emissiveTriangleCount, features, invalidTriangles;
    uint32_t vertexColors;  // 1: scene_vertex_colors holds one entry per vertex
    float totalPower, emissivePower, punctualPower, radius;  // radius of the bounding sphere
    glm::vec4 boundsMin;                                     // xyz; w unused
    glm::vec4 boundsMax;
    // Device addresses of scene_vertices, scene_triangles, scene_bvh, scene_bvh_triangles: the
    // shaders read these through buffer references (no descriptor range limit; issue 28).
    uint64_t vertexAddress, triangleAddress, nodeAddress, bvhTriangleAddress;
};

// scene_environment (SCENE_HAS_ENVIRONMENT): this header, then one vec4 per texel (rgb radiance,
// a = the texel's selection probability P_ij); scene_environment_alias: per texel uvec2(alias,
// floatBitsToUint(keep probability)). core/scene/Environment.h has the mapping and the pdf.
struct EnvironmentHeader {
    uint32_t width, height;
    float rotation;           // radians about +Y
    float selectProbability;  // of picking the environment in next-event estimation
    float pdfScale;           // W H / (2 pi^2): pdf(w) = P_ij * pdfScale / sin(theta)
    float luminanceIntegral;  // for reports and tests
    float pad[2];
};

static_assert(sizeof(Vertex) == 32);
static_assert(sizeof(EnvironmentHeader) == 32);
static_assert(sizeof(Triangle) == 16);
static_assert(sizeof(TextureView) == 32);
static_assert(sizeof(TrianglePositions) == 48);
static_assert(sizeof(Material) == 64);
static_assert(sizeof(Texture) == 16);
static_assert(sizeof(Light) == 64 && offsetof(Light, range) == 12 && offsetof(Light, type) == 28 &&
              offsetof(Light, spotScale) == 44 && offsetof(Light, spotOffset) == 48);
static_assert(sizeof(Info) == 128 && offsetof(Info, totalPower) == 48 &&
              offsetof(Info, boundsMin) == 64 && offsetof(Info, vertexAddress) == 96 &&
              offsetof(Info, bvhTriangleAddress) == 120);  // std140 uvec2: 8-byte aligned

}  // namespace layout

class SceneGpu {
public:
    // Builds the BVH and the light table, then uploads. Throws RuntimeError for inconsistent
    // meshes (indices or material ids out of range) and for texel data beyond the device's
    // storage-buffer range.
    SceneGpu(gpu::Context& context, const Scene& scene, const BvhBuildOptions& bvhOptions = {});
    // With a prebuilt BVH and a light table made with bvh.triangleOrder().
    SceneGpu(gpu::Context& context, const Scene& scene, const Bvh& bvh, const LightTable& lights);
    ~SceneGpu();
    SceneGpu(const SceneGpu&) = delete;
    SceneGpu& operator=(const SceneGpu&) = delete;

    // Binds every scene_* buffer the pipeline declares (others are skipped, so a shader compiled
    // without textures needs no texel buffer).
    void bind(gpu::ComputePipeline& pipeline) const;
    // scene_info, scene_vertices, scene_triangles, scene_bvh, scene_bvh_triangles,
    // scene_materials, scene_textures, scene_texels, scene_lights, scene_emitters.
    static std::vector<std::string> resourceNames();
    // graph::SceneFeature bits of what was uploaded: geometry (any triangle), emissive (an
    // emitting triangle), textures (a material samples a texture with texels), punctual (a
    // light with power > 0), environment, alpha (a triangle's material is MASK with cutoff > 0
    // or BLEND).
    uint32_t features() const { return mFeatures; }
    // SCENE_HAS_TEXTURES / SCENE_HAS_EMISSIVE / SCENE_HAS_PUNCTUAL / SCENE_HAS_VERTEX_COLORS /
    // SCENE_HAS_ENVIRONMENT / SCENE_HAS_ALPHA = "0" or "1".
    std::vector<std::pair<std::string, std::string>> defines() const;
    // A triangle's material is alphaMode BLEND: ray casts are stochastic (a new pass/stop
    // decision per frame), so even primary visibility changes from frame to frame.
    bool hasStochasticAlpha() const { return mStochasticAlpha; }
    // The mesh has per-vertex colours (scene_vertex_colors, SCENE_HAS_VERTEX_COLORS).
    bool hasVertexColors() const { return mVertexColors; }
    // A material reads a normal texture (scene_tangents, SCENE_HAS_NORMAL_MAPS).
    bool hasNormalMaps() const { return mNormalMaps; }
    // The uploaded environment (zeros without one; a black map is not uploaded).
    const layout::EnvironmentHeader& environment() const { return mEnvironment; }

    // Throws RuntimeError (with did-you-mean) for a name not in resourceNames().
    const gpu::Buffer& buffer(std::string_view name) const;
    // Allocated bytes per buffer (empty data still gets 16 bytes), in resourceNames() order.
    std::vector<std::pair<std::string, uint64_t>> memoryStats() const;
    uint64_t totalBytes() const;

    const BvhStats& bvhStats() const { return mBvhStats; }
    // GPU triangle i is mesh triangle triangleOrder()[i]; hit ids are GPU triangle indices.
    const std::vector<uint32_t>& triangleOrder() const { return mTriangleOrder; }
    const layout::Info& info() const { return mInfo; }

private:
    struct Packed;  // every buffer's contents before the upload (SceneGpu.cpp)

    void upload(gpu::Context& context, const Scene& scene, const Bvh& bvh,
                const LightTable& lights);
    // mInfo from what was packed and the BVH's bounds; features follow in setFeatures().
    void describe(const Bvh& bvh, const LightTable& lights, const Packed& packed);
    void setFeatures(const LightTable& lights, const Packed& packed);
    void uploadBuffers(gpu::Context& context, const Bvh& bvh, const LightTable& lights,
                       const Packed& packed);
    // `addressed`: also a device address (no descriptor range limit; checked against the
    // device's largest allocation instead).
    void addBuffer(gpu::Context& context, const std::string& name, const void* data, size_t bytes,
                   bool uniform = false, bool addressed = false);
    // A geometry array: bound, or read through its device address (returned; else 0) when
    // mGeometryByAddress.
    uint64_t addGeometryBuffer(gpu::Context& context, const std::string& name, const void* data,
                               size_t bytes);

    std::vector<std::pair<std::string, std::unique_ptr<gpu::Buffer>>> mBuffers;
    std::vector<uint32_t> mTriangleOrder;
    BvhStats mBvhStats;
    bool mVertexColors = false;
    // Geometry arrays read through device addresses (one exceeds maxStorageBufferRange).
    bool mGeometryByAddress = false;
    bool mNormalMaps = false;
    bool mStochasticAlpha = false;
    layout::Info mInfo{};
    layout::EnvironmentHeader mEnvironment{};
    uint32_t mFeatures = 0;
};

}  // namespace fovea::scene
