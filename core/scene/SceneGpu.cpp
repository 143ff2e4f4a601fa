#include "core/scene/SceneGpu.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numbers>

#include "core/scene/Environment.h"
#include "core/scene/SceneFeatures.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Context.h"
#include "core/vk/Resources.h"

namespace fovea::scene {
namespace {

// Empty data still becomes a valid binding: Vulkan buffers cannot be empty, and a shader that
// keeps a feature compiled in may declare the buffer without ever reading it.
constexpr size_t kMinBufferBytes = 16;

// scene_vertices, scene_triangles, scene_bvh and scene_bvh_triangles are bound unless the scene
// reads them through their addresses (SCENE_GEOMETRY_BY_ADDRESS).
const std::vector<std::string> kResourceNames = {"scene_info",          "scene_vertices",
                                                 "scene_triangles",     "scene_bvh",
                                                 "scene_bvh_triangles", "scene_materials",
                                                 "scene_textures",      "scene_texels",
                                                 "scene_texture_views", "scene_lights",
                                                 "scene_emitters",      "scene_vertex_colors",
                                                 "scene_environment",   "scene_environment_alias",
                                                 "scene_tangents"};

// COLOR_0 as two packUnorm2x16 words (RG, BA): 8 bytes a vertex; 16-bit unorm holds every
// normalized unsigned short exactly and floats to 1.5e-5 (colours are in [0, 1], glTF §3.7.2.1).
glm::uvec2 packColor(const glm::vec4& c) {
    auto unorm16 = [](float v) {
        // NaN fails both comparisons and becomes 0; the loader already clamped to [0, 1].
        const float clamped = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
        return uint32_t(std::lround(clamped * 65535.0f));
    };
    return {unorm16(c.r) | unorm16(c.g) << 16, unorm16(c.b) | unorm16(c.a) << 16};
}

template <class T>
size_t bytesOf(const std::vector<T>& v) {
    return v.size() * sizeof(T);
}

int validTexture(int index, const std::vector<Texture>& textures) {
    return index >= 0 && size_t(index) < textures.size() ? index : -1;
}

// layout::Material::params.w, what the traversal's alpha test compares alpha against (glTF 2.0
// §3.9.4): a ray passes through a texel whose alpha is below it. 0 = opaque (alpha >= 0 always
// meets it; MASK with cutoff 0 is the same); > 0 = MASK's alphaCutoff; -1 = BLEND, whose
// threshold is a fresh random number per ray and hit (docs/scenes.md "Alpha").
float alphaThreshold(const Material& m) {
    if (!m.hasAlphaTest()) return 0.0f;
    return m.alphaMode == AlphaMode::Blend ? -1.0f : m.alphaCutoff;
}

bool hasTexels(const Texture& t) {
    const size_t texels = size_t(t.width) * t.height;
    return texels > 0 && t.rgba8.size() >= texels * 4;
}

layout::Light packLight(const Light& light) {
    layout::Light out{};
    out.position = light.position;
    out.range = std::isfinite(light.range) ? std::max(0.0f, light.range) : 0.0f;
    const float len = glm::length(light.direction);
    // A zero or broken direction falls back to the extension's default (-Z) instead of NaN.
    out.direction =
        len > 0.0f && std::isfinite(len) ? light.direction / len : glm::vec3(0.0f, 0.0f, -1.0f);
    out.type = static_cast<uint32_t>(light.type);
    out.intensity = light.color * light.intensity;
    // KHR_lights_punctual's reference cone falloff; the max() keeps equal cones finite.
    const float cosOuter = std::cos(light.outerConeAngle);
    const float cosInner = std::cos(light.innerConeAngle);
    out.spotScale = 1.0f / std::max(0.001f, cosInner - cosOuter);
    out.spotOffset = -cosOuter * out.spotScale;
    return out;
}

// scene_environment's texel array and scene_environment_alias (layout::EnvironmentHeader);
// both empty for a scene without an emitting environment.
struct EnvironmentUpload {
    std::vector<glm::vec4> texels;
    std::vector<glm::uvec2> alias;  // the row table (height slots), then each row's columns
};

layout::TextureView packTextureView(const TextureView& view) {
    layout::TextureView out{};
    out.scale = 1.0f;
    out.flags = view.sampler.flags();
    if (!view.transform.isIdentity()) {
        out.flags |= layout::kTextureViewTransformed;
        out.row0 = view.transform.row0();
        out.row1 = view.transform.row1();
    }
    return out;
}

// scene_materials and scene_texture_views, and what the shaders need compiled in for them.
struct MaterialUpload {
    std::vector<layout::Material> materials;
    std::vector<layout::TextureView> views;  // kTextureSlots a material; empty without texels
    std::vector<bool> textureUsed;           // per Scene texture
    bool textured = false;      // a material samples a texture with texels (SCENE_HAS_TEXTURES)
    bool normalMapped = false;  // and one reads a normal texture (SCENE_HAS_NORMAL_MAPS)
};

MaterialUpload packMaterials(const std::vector<Material>& materials, const Scene& scene,
                             const LightTable& lights) {
    const TriangleMesh& mesh = scene.mesh;
    MaterialUpload out;
    out.textureUsed.assign(scene.textures.size(), false);
    out.materials.reserve(materials.size());
    out.views.reserve(materials.size() * layout::kTextureSlots);
    const std::vector<double>& density = lights.materialPowerDensity();
    for (size_t m = 0; m < materials.size(); ++m) {
        const Material& mat = materials[m];
        layout::Material g{};
        g.baseColor = mat.baseColor;
        g.emissive = glm::vec4(mat.emissive, m < density.size() ? float(density[m]) : 0.0f);
        g.params = glm::vec4(mat.metallic, mat.roughness, mat.doubleSided ? 1.0f : 0.0f,
                             alphaThreshold(mat));
        g.textures = glm::ivec4(validTexture(mat.baseColorTexture, scene.textures),
                                validTexture(mat.metallicRoughnessTexture, scene.textures),
                                validTexture(mat.emissiveTexture, scene.textures),
                                validTexture(mat.normalTexture, scene.textures));
        // A normal texture needs tangents; a hand-built mesh without them shades unmapped.
        if (mesh.tangents.size() != mesh.positions.size()) g.textures.w = -1;
        out.normalMapped = out.normalMapped || g.textures.w >= 0;
        for (int k = 0; k < 4; ++k) {
            if (g.textures[k] < 0) continue;
            out.textureUsed[g.textures[k]] = true;
            out.textured = out.textured || hasTexels(scene.textures[g.textures[k]]);
        }
        out.materials.push_back(g);
        // The order of g.textures' x, y, z, w (kSceneSlot* in scene_texture.glsl).
        for (const TextureView* view :
             {&mat.baseColorView, &mat.metallicRoughnessView, &mat.emissiveView, &mat.normalView})
            out.views.push_back(packTextureView(*view));
        out.views.back().scale = mat.normalScale;
    }
    // The shader reads scene_tangents only through textures.w: without texels (or tangents) no
    // material may name a normal texture; without texels nothing reads the views.
    out.normalMapped = out.normalMapped && out.textured;
    if (!out.normalMapped)
        for (layout::Material& g : out.materials) g.textures.w = -1;
    if (!out.textured) out.views.clear();
    return out;
}

glm::uvec2 packAliasSlot(const AliasSlot& slot) {
    return glm::uvec2(slot.alias, std::bit_cast<uint32_t>(float(slot.prob)));
}

EnvironmentUpload packEnvironment(const Scene& scene, const LightTable& lights, float radius,
                                  layout::EnvironmentHeader& header) {
    header = layout::EnvironmentHeader{};
    EnvironmentUpload out;
    if (!scene.environment) return out;
    const EnvironmentMap& map = *scene.environment;
    const EnvironmentDistribution distribution(map);
    if (distribution.empty()) return out;  // black: lights nothing (loadEnvironment warned)
    const size_t n = map.radiance.size();
    out.texels.resize(n);
    for (size_t k = 0; k < n; ++k)
        out.texels[k] = glm::vec4(map.radiance[k], float(distribution.texelProbability()[k]));
    out.alias.reserve(distribution.rows().size() + distribution.columns().size());
    for (const AliasSlot& slot : distribution.rows()) out.alias.push_back(packAliasSlot(slot));
    for (const AliasSlot& slot : distribution.columns()) out.alias.push_back(packAliasSlot(slot));
    header.width = map.width;
    header.height = map.height;
    header.rotation = map.rotation;
    // One-sample choice between the environment and the alias table of the other lights, by
    // power in LightTable's units (Environment.h); 1 when nothing else emits. Each side keeps
    // at least kMinLightSelect: power alone starves one of them (the environment's power grows
    // with the scene's radius squared; under a 1000-unit ground plane a 0.36 m^2 lamp got
    // 2e-8, which rounds to 0 in float, so next-event estimation never sampled it and
    // emitterSampling = light lost its light entirely).
    constexpr double kMinLightSelect = 0.1;
    const double envPower = distribution.power(radius);
    const double others = lights.entries().empty() ? 0.0 : lights.totalPower();
    header.selectProbability =
        float(others > 0.0 ? std::clamp(envPower / (envPower + others), kMinLightSelect,
                                        1.0 - kMinLightSelect)
                           : 1.0);
    const double pi = std::numbers::pi;
    header.pdfScale = float(double(map.width) * map.height / (2.0 * pi * pi));
    header.luminanceIntegral = float(distribution.luminanceIntegral());
    return out;
}

void checkMeshMatchesBvh(const TriangleMesh& mesh, const Bvh& bvh) {
    const std::vector<uint32_t>& order = bvh.triangleOrder();
    if (order.size() != mesh.triangles.size())
        throw RuntimeError("SceneGpu: the BVH was built for " + std::to_string(order.size()) +
                           " triangles but the scene has " + std::to_string(mesh.triangles.size()));
    if (mesh.materialIds.size() != mesh.triangles.size())
        throw RuntimeError("SceneGpu: " + std::to_string(mesh.materialIds.size()) +
                           " material ids for " + std::to_string(mesh.triangles.size()) +
                           " triangles");
}

std::vector<layout::Vertex> packVertices(const TriangleMesh& mesh) {
    std::vector<layout::Vertex> vertices(mesh.positions.size());
    for (size_t v = 0; v < vertices.size(); ++v) {
        // Loaders always fill normals and uvs; hand-built meshes may not (zero normal = the
        // shader falls back to the geometric normal).
        const glm::vec3 n = v < mesh.normals.size() ? mesh.normals[v] : glm::vec3(0.0f);
        const glm::vec2 uv = v < mesh.uvs.size() ? mesh.uvs[v] : glm::vec2(0.0f);
        vertices[v] = {glm::vec4(mesh.positions[v], uv.x), glm::vec4(n, uv.y)};
    }
    return vertices;
}

// `count` packed colours, white past the end of mesh.colors.
std::vector<glm::uvec2> packVertexColors(const TriangleMesh& mesh, size_t count) {
    std::vector<glm::uvec2> colors(count);
    for (size_t v = 0; v < colors.size(); ++v)
        colors[v] = packColor(v < mesh.colors.size() ? mesh.colors[v] : glm::vec4(1.0f));
    return colors;
}

// scene_triangles and scene_bvh_triangles, both in BVH order.
struct TriangleUpload {
    std::vector<layout::Triangle> triangles;
    std::vector<layout::TrianglePositions> positions;
    bool alphaTested = false;      // a triangle whose material has an alpha test
    bool stochasticAlpha = false;  // a triangle whose material is BLEND
};

TriangleUpload packTriangles(const TriangleMesh& mesh, const std::vector<uint32_t>& order,
                             const std::vector<layout::Material>& gpuMaterials) {
    TriangleUpload out;
    out.triangles.resize(order.size());
    out.positions.resize(order.size());
    for (size_t i = 0; i < order.size(); ++i) {
        const uint32_t t = order[i];
        const glm::uvec3 tri = mesh.triangles[t];  // indices were checked by the BVH build
        const uint32_t material = mesh.materialIds[t];
        if (material >= gpuMaterials.size())
            throw RuntimeError("SceneGpu: triangle " + std::to_string(t) + " uses material " +
                               std::to_string(material) + " of " +
                               std::to_string(gpuMaterials.size()));
        out.triangles[i] = {tri, material};
        const glm::vec3 v0 = mesh.positions[tri.x];
        // The traversal reads v0 anyway: its w tells it whether to look the material up.
        const bool alphaTested = gpuMaterials[material].params.w != 0.0f;
        out.alphaTested = out.alphaTested || alphaTested;
        out.stochasticAlpha = out.stochasticAlpha || gpuMaterials[material].params.w < 0.0f;
        out.positions[i] = {glm::vec4(v0, alphaTested ? 1.0f : 0.0f),
                            glm::vec4(mesh.positions[tri.y] - v0, 0.0f),
                            glm::vec4(mesh.positions[tri.z] - v0, 0.0f)};
    }
    return out;
}

// scene_textures and scene_texels.
struct TextureUpload {
    std::vector<layout::Texture> table;  // one entry per Scene texture
    std::vector<uint32_t> texels;        // RGBA8, one uint a texel
};

// Textures: every used one packed into one RGBA8 texel array (no descriptor indexing on
// lavapipe, see docs/scene-gpu.md); unused ones keep a table entry without texels so
// material indices stay Scene indices.
TextureUpload packTextures(const gpu::Context& context, const std::vector<Texture>& textures,
                           const std::vector<bool>& textureUsed) {
    TextureUpload out;
    out.table.assign(textures.size(), layout::Texture{});
    size_t texelCount = 0;
    for (size_t t = 0; t < textures.size(); ++t)
        if (textureUsed[t] && hasTexels(textures[t]))
            texelCount += size_t(textures[t].width) * textures[t].height;
    const uint64_t maxRange = context.limits().maxStorageBufferRange;
    if (texelCount * 4 > maxRange || texelCount > UINT32_MAX)
        throw RuntimeError("SceneGpu: scene textures need " + std::to_string(texelCount * 4 >> 20) +
                           " MiB of texels but '" + context.deviceName() + "' binds at most " +
                           std::to_string(maxRange >> 20) + " MiB per storage buffer");
    out.texels.resize(texelCount);
    size_t offset = 0;
    for (size_t t = 0; t < textures.size(); ++t) {
        const Texture& tex = textures[t];
        if (!textureUsed[t] || !hasTexels(tex)) continue;
        const size_t count = size_t(tex.width) * tex.height;
        // Bytes R,G,B,A become one little-endian uint: unpackUnorm4x8 reads R from the low byte.
        std::memcpy(out.texels.data() + offset, tex.rgba8.data(), count * 4);
        out.table[t] = {static_cast<uint32_t>(offset), tex.width, tex.height, 0u};
        offset += count;
    }
    return out;
}

std::vector<layout::Light> packLights(const std::vector<Light>& lights) {
    std::vector<layout::Light> gpuLights;
    gpuLights.reserve(lights.size());
    for (const Light& light : lights) gpuLights.push_back(packLight(light));
    return gpuLights;
}

// The header and the texels in one buffer (the GLSL block's fixed part, then its array).
std::vector<glm::vec4> environmentBufferData(const layout::EnvironmentHeader& header,
                                             const EnvironmentUpload& environment) {
    std::vector<glm::vec4> environmentData(sizeof(layout::EnvironmentHeader) / sizeof(glm::vec4));
    std::memcpy(environmentData.data(), &header, sizeof(header));
    environmentData.insert(environmentData.end(), environment.texels.begin(),
                           environment.texels.end());
    return environmentData;
}

}  // namespace

// Every scene_* buffer's contents in the shaders' layouts (SceneGpu.h), before the upload.
struct SceneGpu::Packed {
    MaterialUpload materials;
    std::vector<layout::Vertex> vertices;
    std::vector<glm::vec4> tangents;  // empty unless a material reads a normal texture
    std::vector<glm::uvec2> colors;   // empty unless the mesh has vertex colours
    TriangleUpload triangles;
    TextureUpload textures;
    std::vector<layout::Light> lights;
    EnvironmentUpload environment;
};

SceneGpu::SceneGpu(gpu::Context& context, const Scene& scene, const BvhBuildOptions& bvhOptions) {
    const Bvh bvh(scene.mesh, bvhOptions);
    const LightTable lights(scene, bvh.triangleOrder());
    upload(context, scene, bvh, lights);
}

SceneGpu::SceneGpu(gpu::Context& context, const Scene& scene, const Bvh& bvh,
                   const LightTable& lights) {
    upload(context, scene, bvh, lights);
}

SceneGpu::~SceneGpu() = default;

std::vector<std::string> SceneGpu::resourceNames() {
    return kResourceNames;
}

uint64_t SceneGpu::addGeometryBuffer(gpu::Context& context, const std::string& name,
                                     const void* data, size_t bytes) {
    addBuffer(context, name, data, bytes, false, mGeometryByAddress);
    return mGeometryByAddress ? mBuffers.back().second->deviceAddress() : 0;
}

void SceneGpu::addBuffer(gpu::Context& context, const std::string& name, const void* data,
                         size_t bytes, bool uniform, bool addressed) {
    vk::BufferUsageFlags usage = (uniform ? vk::BufferUsageFlagBits::eUniformBuffer
                                          : vk::BufferUsageFlagBits::eStorageBuffer) |
                                 vk::BufferUsageFlagBits::eTransferSrc |
                                 vk::BufferUsageFlagBits::eTransferDst;
    if (addressed) usage |= vk::BufferUsageFlagBits::eShaderDeviceAddress;
    // Round up to 16 so the tail of a vec4 array never straddles the end.
    const size_t size = std::max(kMinBufferBytes, (bytes + 15) / 16 * 16);
    // A scene larger than the device binds is a clear error naming the buffer and the limit,
    // before any allocation (issue 28: never a crash or a driver error).
    const auto& limits = context.limits();
    const uint64_t range = addressed ? context.maxAllocationBytes()
                           : uniform ? limits.maxUniformBufferRange
                                     : limits.maxStorageBufferRange;
    if (size > range)
        throw RuntimeError("SceneGpu: the scene's '" + name + "' needs " + std::to_string(size) +
                           " bytes (" + std::to_string(mTriangleOrder.size()) +
                           " triangles) but '" + context.deviceName() + "' binds at most " +
                           std::to_string(range) + " bytes per " +
                           (addressed ? "allocation"
                            : uniform ? "uniform buffer"
                                      : "storage buffer") +
                           ": render a smaller scene or use a device with a larger limit");
    auto buffer = std::make_unique<gpu::Buffer>(context, size, usage, false, name);
    if (bytes > 0) buffer->upload(context, data, bytes);
    mBuffers.emplace_back(name, std::move(buffer));
}

void SceneGpu::upload(gpu::Context& context, const Scene& scene, const Bvh& bvh,
                      const LightTable& lights) {
    const TriangleMesh& mesh = scene.mesh;
    checkMeshMatchesBvh(mesh, bvh);
    mTriangleOrder = bvh.triangleOrder();
    mBvhStats = bvh.stats();

    Packed packed;
    // Materials: glTF's default material stands in when a hand-built scene has none.
    const std::vector<Material> fallback(1);
    const std::vector<Material>& materials = scene.materials.empty() ? fallback : scene.materials;
    packed.materials = packMaterials(materials, scene, lights);

    // Geometry in BVH order.
    packed.vertices = packVertices(mesh);
    // Vertex colours only when the mesh has them (else an empty binding, compiled out).
    // Tangents only when a material's normal texture will read them (SCENE_HAS_NORMAL_MAPS).
    mNormalMaps = packed.materials.normalMapped;
    if (mNormalMaps) packed.tangents = mesh.tangents;
    mVertexColors = !mesh.colors.empty();
    packed.colors = packVertexColors(mesh, mVertexColors ? packed.vertices.size() : 0);
    packed.triangles = packTriangles(mesh, mTriangleOrder, packed.materials.materials);
    mStochasticAlpha = packed.triangles.stochasticAlpha;

    packed.textures = packTextures(context, scene.textures, packed.materials.textureUsed);
    packed.lights = packLights(scene.lights);

    describe(bvh, lights, packed);
    packed.environment = packEnvironment(scene, lights, mInfo.radius, mEnvironment);
    setFeatures(lights, packed);
    uploadBuffers(context, bvh, lights, packed);
}

void SceneGpu::describe(const Bvh& bvh, const LightTable& lights, const Packed& packed) {
    const Bounds& bounds = bvh.bounds();
    mInfo = layout::Info{};
    mInfo.vertexCount = static_cast<uint32_t>(packed.vertices.size());
    mInfo.triangleCount = static_cast<uint32_t>(packed.triangles.triangles.size());
    mInfo.nodeCount = static_cast<uint32_t>(bvh.nodes().size());
    mInfo.materialCount = static_cast<uint32_t>(packed.materials.materials.size());
    mInfo.textureCount = static_cast<uint32_t>(packed.textures.table.size());
    mInfo.texelCount = static_cast<uint32_t>(packed.textures.texels.size());
    mInfo.lightCount = static_cast<uint32_t>(packed.lights.size());
    mInfo.emitterCount = static_cast<uint32_t>(lights.entries().size());
    mInfo.emissiveTriangleCount = lights.emissiveTriangleCount();
    mInfo.invalidTriangles = bvh.stats().invalidTriangles;
    mInfo.vertexColors = mVertexColors ? 1u : 0u;
    mInfo.totalPower = static_cast<float>(lights.totalPower());
    mInfo.emissivePower = static_cast<float>(lights.emissivePower());
    mInfo.punctualPower = static_cast<float>(lights.punctualPower());
    if (!bounds.empty()) {
        mInfo.boundsMin = glm::vec4(bounds.min, 0.0f);
        mInfo.boundsMax = glm::vec4(bounds.max, 0.0f);
        mInfo.radius = 0.5f * glm::length(bounds.extent());
    }
}

void SceneGpu::setFeatures(const LightTable& lights, const Packed& packed) {
    mFeatures = 0;
    if (!packed.triangles.triangles.empty()) mFeatures |= kSceneGeometry;
    if (lights.emissiveTriangleCount() > 0) mFeatures |= kSceneEmissive;
    if (packed.materials.textured) mFeatures |= kSceneTextures;
    if (lights.punctualLightCount() > 0) mFeatures |= kScenePunctual;
    if (!packed.environment.texels.empty()) mFeatures |= kSceneEnvironment;
    if (packed.triangles.alphaTested) mFeatures |= kSceneAlpha;
    mInfo.features = mFeatures;
}

void SceneGpu::uploadBuffers(gpu::Context& context, const Bvh& bvh, const LightTable& lights,
                             const Packed& packed) {
    const MaterialUpload& materials = packed.materials;
    const TriangleUpload& triangles = packed.triangles;
    const TextureUpload& textures = packed.textures;
    mBuffers.clear();
    // The arrays that grow with the triangle count are read through their addresses when one of
    // them is larger than a storage descriptor may bind (a 10M-triangle scene on lavapipe).
    const uint64_t range = context.limits().maxStorageBufferRange;
    mGeometryByAddress = std::max({bytesOf(packed.vertices), bytesOf(triangles.triangles),
                                   bytesOf(bvh.nodes()), bytesOf(triangles.positions)}) > range;
    if (mGeometryByAddress && !context.features().bufferDeviceAddress)
        throw RuntimeError("SceneGpu: the scene's geometry is larger than '" +
                           context.deviceName() + "' binds per storage buffer (" +
                           std::to_string(range) +
                           " bytes) and the device lacks "
                           "bufferDeviceAddress to read it otherwise");
    // First: scene_info carries their addresses.
    mInfo.vertexAddress = addGeometryBuffer(context, "scene_vertices", packed.vertices.data(),
                                            bytesOf(packed.vertices));
    mInfo.triangleAddress = addGeometryBuffer(
        context, "scene_triangles", triangles.triangles.data(), bytesOf(triangles.triangles));
    mInfo.nodeAddress =
        addGeometryBuffer(context, "scene_bvh", bvh.nodes().data(), bytesOf(bvh.nodes()));
    mInfo.bvhTriangleAddress = addGeometryBuffer(
        context, "scene_bvh_triangles", triangles.positions.data(), bytesOf(triangles.positions));
    addBuffer(context, "scene_info", &mInfo, sizeof(mInfo), true);
    std::rotate(mBuffers.begin(), mBuffers.end() - 1, mBuffers.end());  // scene_info first
    addBuffer(context, "scene_materials", materials.materials.data(), bytesOf(materials.materials));
    addBuffer(context, "scene_textures", textures.table.data(), bytesOf(textures.table));
    addBuffer(context, "scene_texels", textures.texels.data(), bytesOf(textures.texels));
    addBuffer(context, "scene_texture_views", materials.views.data(), bytesOf(materials.views));
    addBuffer(context, "scene_lights", packed.lights.data(), bytesOf(packed.lights));
    addBuffer(context, "scene_emitters", lights.entries().data(), bytesOf(lights.entries()));
    addBuffer(context, "scene_vertex_colors", packed.colors.data(), bytesOf(packed.colors));
    const std::vector<glm::vec4> environmentData =
        environmentBufferData(mEnvironment, packed.environment);
    addBuffer(context, "scene_environment", environmentData.data(), bytesOf(environmentData));
    addBuffer(context, "scene_environment_alias", packed.environment.alias.data(),
              bytesOf(packed.environment.alias));
    addBuffer(context, "scene_tangents", packed.tangents.data(), bytesOf(packed.tangents));
}

void SceneGpu::bind(gpu::ComputePipeline& pipeline) const {
    for (const auto& [name, buffer] : mBuffers)
        if (pipeline.hasBinding(name)) pipeline.bind(name, *buffer);
}

std::vector<std::pair<std::string, std::string>> SceneGpu::defines() const {
    auto flag = [&](uint32_t bit) { return std::string((mFeatures & bit) ? "1" : "0"); };
    return {{"SCENE_HAS_TEXTURES", flag(kSceneTextures)},
            {"SCENE_HAS_EMISSIVE", flag(kSceneEmissive)},
            {"SCENE_HAS_PUNCTUAL", flag(kScenePunctual)},
            {"SCENE_HAS_VERTEX_COLORS", mVertexColors ? "1" : "0"},
            {"SCENE_HAS_NORMAL_MAPS", mNormalMaps ? "1" : "0"},
            {"SCENE_HAS_ENVIRONMENT", flag(kSceneEnvironment)},
            {"SCENE_HAS_ALPHA", flag(kSceneAlpha)},
            {"SCENE_GEOMETRY_BY_ADDRESS", mGeometryByAddress ? "1" : "0"}};
}

const gpu::Buffer& SceneGpu::buffer(std::string_view name) const {
    for (const auto& [n, buffer] : mBuffers)
        if (n == name) return *buffer;
    std::vector<std::string> names;
    for (const auto& [n, buffer] : mBuffers) names.push_back(n);
    throw RuntimeError("SceneGpu has no buffer '" + std::string(name) + "'" +
                       didYouMean(name, names));
}

std::vector<std::pair<std::string, uint64_t>> SceneGpu::memoryStats() const {
    std::vector<std::pair<std::string, uint64_t>> out;
    for (const auto& [name, buffer] : mBuffers) out.emplace_back(name, buffer->size());
    return out;
}

uint64_t SceneGpu::totalBytes() const {
    uint64_t total = 0;
    for (const auto& [name, buffer] : mBuffers) total += buffer->size();
    return total;
}

}  // namespace fovea::scene
