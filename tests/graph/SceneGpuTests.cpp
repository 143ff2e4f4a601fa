// LightTable tests (alias table, power estimates, selection pdfs) and SceneGpu tests (buffers,
// features and defines, GPU texture sampling against a CPU bilinear reference, GPU light
// sampling against the table).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/glm.hpp>
#include <map>
#include <numbers>
#include <random>
#include <vector>

#include "core/graph/Pass.h"
#include "core/scene/Bvh.h"
#include "core/scene/LightTable.h"
#include "core/scene/SceneGpu.h"
#include "core/scene/TextureSampling.h"
#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Context.h"
#include "core/vk/Resources.h"
#include "tests/graph/GpuTestFixture.h"
#include "tests/unit/SceneTestUtil.h"

#if __has_include("core/scene/SceneLoader.h")
#include <filesystem>
#include <iostream>

#include "core/scene/SceneLoader.h"
#define FOVEA_TEST_HAS_SCENE_LOADER 1
#endif

using namespace fovea;
using namespace fovea::scene;
using namespace fovea::test;

namespace {

constexpr double kPi = std::numbers::pi;

// Probability the alias table gives each index: column i with 1/N, kept with prob, else alias.
std::vector<double> impliedProbabilities(const std::vector<AliasSlot>& table) {
    std::vector<double> p(table.size(), 0.0);
    const double n = double(table.size());
    for (size_t i = 0; i < table.size(); ++i) {
        p[i] += table[i].prob / n;
        p[table[i].alias] += (1.0 - table[i].prob) / n;
    }
    return p;
}

Material emissiveMaterial(glm::vec3 emission, bool doubleSided) {
    Material m;
    m.emissive = emission;
    m.doubleSided = doubleSided;
    return m;
}

Texture makeTexture(uint32_t w, uint32_t h, uint32_t seed) {
    Texture t;
    t.name = "tex" + std::to_string(seed);
    t.width = w;
    t.height = h;
    std::mt19937 rng(seed);
    for (uint32_t i = 0; i < w * h * 4; ++i) t.rgba8.push_back(static_cast<uint8_t>(rng() & 0xFF));
    return t;
}

gpu::Buffer hostBuffer(gpu::Context& ctx, size_t bytes, const char* name) {
    return gpu::Buffer(ctx, bytes,
                       vk::BufferUsageFlagBits::eStorageBuffer |
                           vk::BufferUsageFlagBits::eTransferSrc |
                           vk::BufferUsageFlagBits::eTransferDst,
                       false, name);
}

}  // namespace

// --- LightTable (CPU) -------------------------------------------------------------------------

TEST(LightTable, AliasTableIsExact) {
    const std::vector<double> w = {0.0, 1.0, 2.0, 3.5, 0.001, 10.0, 0.0, 7.0, 1e-9, 4.0};
    const auto table = buildAliasTable(w);
    ASSERT_EQ(table.size(), w.size());
    double sum = 0.0;
    for (double x : w) sum += x;
    const auto p = impliedProbabilities(table);
    double total = 0.0;
    for (size_t i = 0; i < w.size(); ++i) {
        EXPECT_NEAR(p[i], w[i] / sum, 1e-12) << i;
        total += p[i];
    }
    EXPECT_NEAR(total, 1.0, 1e-12);
}

TEST(LightTable, AliasSamplingFrequencies) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> weight(0.0, 1.0);
    std::vector<double> w(64);
    for (auto& x : w) x = std::pow(weight(rng), 3.0);  // skewed, several tiny weights
    const auto table = buildAliasTable(w);
    double sum = 0.0;
    for (double x : w) sum += x;
    const uint32_t samples = 1000000;
    std::vector<uint32_t> counts(w.size(), 0);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (uint32_t s = 0; s < samples; ++s) {
        // The GPU's arithmetic: float column and coin.
        const uint32_t column =
            std::min(uint32_t(unit(rng) * float(w.size())), uint32_t(w.size() - 1));
        const bool keep = unit(rng) < float(table[column].prob);
        ++counts[keep ? column : table[column].alias];
    }
    double chi2 = 0.0;
    uint32_t dof = 0;
    for (size_t i = 0; i < w.size(); ++i) {
        const double expected = samples * w[i] / sum;
        if (expected < 5.0) continue;  // chi-square needs populated cells
        chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
        ++dof;
    }
    // Mean dof, standard deviation sqrt(2 dof): 6 sigma is a bug, not bad luck.
    EXPECT_LT(chi2, dof + 6.0 * std::sqrt(2.0 * dof)) << "dof " << dof;
}

TEST(LightTable, AliasRejectsBadWeights) {
    EXPECT_TRUE(buildAliasTable({}).empty());
    EXPECT_TRUE(buildAliasTable({0.0, 0.0}).empty());
    EXPECT_TRUE(buildAliasTable({1.0, -1.0}).empty());
    EXPECT_TRUE(buildAliasTable({1.0, std::nan("")}).empty());
    const auto one = buildAliasTable({3.0});
    ASSERT_EQ(one.size(), 1u);
    EXPECT_EQ(one[0].prob, 1.0);
}

TEST(LightTable, PowersAndPdfs) {
    Scene scene;
    scene.materials = {Material{}, emissiveMaterial({1, 1, 1}, false),
                       emissiveMaterial({0, 2, 0}, true)};
    addTriangle(scene.mesh, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1);  // area 0.5
    addTriangle(scene.mesh, {0, 0, 5}, {2, 0, 5}, {0, 2, 5}, 2);  // area 2
    addTriangle(scene.mesh, {0, 0, 0}, {1, 0, 0}, {0, 0, 1}, 0);  // not emissive
    addTriangle(scene.mesh, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}, 1);  // zero area: left out
    Light point;
    point.intensity = 10.0f;
    point.color = {1, 0, 0};
    Light spot;
    spot.type = Light::Type::Spot;
    spot.intensity = 5.0f;
    Light sun;
    sun.type = Light::Type::Directional;
    sun.intensity = 2.0f;
    Light dark;
    dark.intensity = 0.0f;
    scene.lights = {point, spot, sun, dark};
    const std::vector<uint32_t> order = {3, 2, 1, 0};  // GPU position -> mesh triangle

    const LightTable table(scene, order);
    ASSERT_EQ(table.entries().size(), 5u);
    EXPECT_EQ(table.emissiveTriangleCount(), 2u);
    EXPECT_EQ(table.punctualLightCount(), 3u);
    // Entries name GPU positions: mesh triangle 1 sits at position 2, triangle 0 at 3.
    EXPECT_EQ(table.entries()[0].light, 2u);
    EXPECT_EQ(table.entries()[1].light, 3u);
    EXPECT_EQ(table.entries()[2].light, kEmitterPunctualBit | 0u);
    EXPECT_EQ(table.entries()[4].light, kEmitterPunctualBit | 2u);

    const double triB = kPi * 2.0 * (0.7152 * 2.0) * 2.0;  // double-sided
    const double triA = kPi * 0.5 * 1.0;
    EXPECT_NEAR(table.emissivePower(), triA + triB, 1e-9);
    const double pointPower = 4.0 * kPi * 10.0 * 0.2126;
    const double spotPower = 2.0 * kPi * (1.0 - std::cos(kPi / 4.0)) * 5.0;
    Bounds bounds;
    for (const auto& p : scene.mesh.positions) bounds.grow(p);
    const double r = 0.5 * glm::length(glm::dvec3(bounds.extent()));
    const double sunPower = kPi * r * r * 2.0;
    EXPECT_NEAR(table.punctualPowers()[0], pointPower, 1e-9);
    EXPECT_NEAR(table.punctualPowers()[1], spotPower, 1e-6);  // float cone angle
    EXPECT_NEAR(table.punctualPowers()[2], sunPower, 1e-6);
    EXPECT_EQ(table.punctualPowers()[3], 0.0);
    EXPECT_NEAR(table.punctualPower(), pointPower + spotPower + sunPower, 1e-6);

    double pdfSum = 0.0;
    for (const auto& e : table.entries()) pdfSum += e.pdf;
    EXPECT_NEAR(pdfSum, 1.0, 1e-6);
    EXPECT_NEAR(table.entries()[0].pdf, triB / table.totalPower(), 1e-7);
    // The set choice the docs state: P(emissive set) = Phi_e / Phi_total.
    EXPECT_NEAR(table.entries()[0].pdf + table.entries()[1].pdf,
                table.emissivePower() / table.totalPower(), 1e-6);
    // Density per material: pdf of a triangle = density * area / total.
    EXPECT_NEAR(table.materialPowerDensity()[2] * 2.0 / table.totalPower(), table.entries()[0].pdf,
                1e-7);
    EXPECT_EQ(table.materialPowerDensity()[0], 0.0);

    std::vector<double> implied(table.entries().size(), 0.0);
    const double n = double(implied.size());
    for (size_t i = 0; i < implied.size(); ++i) {
        implied[i] += table.entries()[i].aliasProb / n;
        implied[table.entries()[i].alias] += (1.0 - table.entries()[i].aliasProb) / n;
    }
    for (size_t i = 0; i < implied.size(); ++i)
        EXPECT_NEAR(implied[i], table.entries()[i].pdf, 1e-6) << i;
}

TEST(LightTable, TexturedEmissionUsesTheAverage) {
    Scene scene;
    Texture t;
    t.width = 2;
    t.height = 1;
    t.rgba8 = {255, 255, 255, 255, 0, 0, 0, 255};  // white and black: linear mean 0.5
    scene.textures = {t};
    Material m = emissiveMaterial({4, 4, 4}, false);
    m.emissiveTexture = 0;
    scene.materials = {m};
    addTriangle(scene.mesh, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
    const LightTable table(scene);
    EXPECT_NEAR(table.emissivePower(), kPi * 0.5 * 4.0 * 0.5, 1e-9);
    EXPECT_NEAR(LightTable::averageLinearColor(t).g, 0.5, 1e-12);
}

TEST(LightTable, NothingEmits) {
    const Scene scene = sceneFromMesh(gridMesh(4));
    const LightTable table(scene);
    EXPECT_TRUE(table.entries().empty());
    EXPECT_EQ(table.totalPower(), 0.0);
    EXPECT_THROW(LightTable(scene, {0, 1}), RuntimeError);
}

// --- SceneGpu ---------------------------------------------------------------------------------

namespace {

class SceneGpuTest : public GpuTest {};

// A scene with every feature: textured base colour, emissive triangles, punctual lights.
Scene fullScene() {
    Scene scene = sceneFromMesh(closedBox(2));
    scene.textures = {makeTexture(5, 3, 1), makeTexture(4, 4, 2), makeTexture(1, 1, 3)};
    Material textured;
    textured.baseColor = {0.5f, 0.25f, 1.0f, 1.0f};
    textured.baseColorTexture = 0;
    textured.metallicRoughnessTexture = 1;
    textured.roughness = 0.5f;
    Material glow = emissiveMaterial({2, 2, 2}, false);
    glow.emissiveTexture = 2;
    scene.materials = {Material{}, textured, glow};
    addTriangle(scene.mesh, {-0.5f, -0.5f, 0.9f}, {-0.5f, 0.5f, 0.9f}, {0.5f, -0.5f, 0.9f}, 2);
    scene.mesh.materialIds[0] = 1;
    Light point;
    point.position = {0, 0.5f, 0};
    scene.lights = {point};
    return scene;
}

}  // namespace

TEST_F(SceneGpuTest, BuffersFeaturesAndDefines) {
    const SceneGpu plain(ctx(), sceneFromMesh(gridMesh(8)));
    EXPECT_EQ(plain.features(), uint32_t(graph::kSceneGeometry));
    for (const auto& [name, value] : plain.defines()) EXPECT_EQ(value, "0") << name;
    const auto names = SceneGpu::resourceNames();
    ASSERT_EQ(names.size(), 15u);
    const auto stats = plain.memoryStats();
    ASSERT_EQ(stats.size(), names.size());
    uint64_t total = 0;
    for (size_t i = 0; i < names.size(); ++i) {
        EXPECT_EQ(stats[i].first, names[i]);
        EXPECT_GE(stats[i].second, 16u) << names[i];
        EXPECT_EQ(plain.buffer(names[i]).size(), stats[i].second);
        total += stats[i].second;
    }
    EXPECT_EQ(plain.totalBytes(), total);
    EXPECT_EQ(plain.buffer("scene_bvh").size(), plain.bvhStats().nodeCount * 32u);
    EXPECT_EQ(plain.buffer("scene_vertices").size(), 81u * 32u);
    EXPECT_EQ(plain.info().triangleCount, 128u);
    try {
        plain.buffer("scene_bvhh");
        FAIL() << "expected RuntimeError";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("did you mean 'scene_bvh'"), std::string::npos)
            << e.what();
    }

    const SceneGpu full(ctx(), fullScene());
    EXPECT_EQ(full.features(), uint32_t(graph::kSceneGeometry | graph::kSceneEmissive |
                                        graph::kSceneTextures | graph::kScenePunctual));
    // Everything but COLOR_0, normal maps, an environment and alpha.
    for (const auto& [name, value] : full.defines()) {
        const bool absent = name == "SCENE_HAS_VERTEX_COLORS" || name == "SCENE_HAS_NORMAL_MAPS" ||
                            name == "SCENE_HAS_ENVIRONMENT" || name == "SCENE_HAS_ALPHA" ||
                            name == "SCENE_GEOMETRY_BY_ADDRESS";
        EXPECT_EQ(value, absent ? "0" : "1") << name;
    }
    EXPECT_EQ(full.info().emitterCount, 2u);
    EXPECT_EQ(full.buffer("scene_texels").size(), (15u + 16u + 1u) * 4u);
}

TEST_F(SceneGpuTest, EmptySceneHasValidBuffers) {
    Scene scene;  // no triangles, no materials
    const SceneGpu empty(ctx(), scene);
    EXPECT_EQ(empty.features(), 0u);
    for (const auto& [name, bytes] : empty.memoryStats()) EXPECT_GE(bytes, 16u) << name;
    EXPECT_EQ(empty.info().nodeCount, 1u);
}

TEST_F(SceneGpuTest, CompiledOutFeaturesNeedNoBuffers) {
    const SceneGpu plain(ctx(), sceneFromMesh(gridMesh(4)));
    gpu::ComputePipeline lean(ctx(), "test/scene_texture.comp", plain.defines());
    for (const char* name : {"scene_textures", "scene_texels", "scene_lights", "scene_emitters"})
        EXPECT_FALSE(lean.hasBinding(name)) << name;
    EXPECT_TRUE(lean.hasBinding("scene_materials"));
    gpu::ComputePipeline everything(ctx(), "test/scene_texture.comp");
    for (const auto& name : SceneGpu::resourceNames()) {
        if (name == "scene_bvh" || name == "scene_bvh_triangles") continue;  // no traversal
        EXPECT_TRUE(everything.hasBinding(name)) << name;
    }
    // Both bind and run: a texture lookup without textures returns 1.
    std::vector<glm::vec4> query = {glm::vec4(0.3f, 0.7f, 0.0f, 1.0f)};
    int zero = 0;
    std::memcpy(&query[0].z, &zero, 4);
    for (gpu::ComputePipeline* pipe : {&lean, &everything}) {
        gpu::Buffer q = hostBuffer(ctx(), 16, "queries");
        gpu::Buffer r = hostBuffer(ctx(), 16, "results");
        q.upload(ctx(), query.data(), 16);
        plain.bind(*pipe);
        pipe->bind("test_queries", q).bind("test_results", r).set("count", 1u);
        ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) { pipe->dispatch(cmd, 1); });
        EXPECT_EQ(r.downloadAs<glm::vec4>(ctx())[0], glm::vec4(1.0f));
    }
}

namespace {

// CPU reference of sceneSampleTexture: the same float coordinate arithmetic, double filtering.
glm::dvec4 referenceSample(const Texture& t, glm::vec2 uv, bool srgb) {
    auto texel = [&](int x, int y) {
        const uint8_t* p = &t.rgba8[(size_t(y) * t.width + x) * 4];
        glm::dvec4 c(p[0] / 255.0, p[1] / 255.0, p[2] / 255.0, p[3] / 255.0);
        if (srgb)
            for (int k = 0; k < 3; ++k) c[k] = LightTable::srgbToLinear(c[k]);
        return c;
    };
    const glm::vec2 size(float(t.width), float(t.height));
    const glm::vec2 st = (uv - glm::floor(uv)) * size - 0.5f;
    const glm::vec2 cell = glm::floor(st);
    const glm::vec2 f = st - cell;
    const glm::ivec2 i0(cell), sz(t.width, t.height);
    glm::ivec2 lo, hi;
    for (int k = 0; k < 2; ++k) {
        lo[k] = i0[k] < 0 ? sz[k] - 1 : i0[k];
        hi[k] = i0[k] + 1 >= sz[k] ? 0 : i0[k] + 1;
    }
    const glm::dvec4 top = glm::mix(texel(lo.x, lo.y), texel(hi.x, lo.y), double(f.x));
    const glm::dvec4 bottom = glm::mix(texel(lo.x, hi.y), texel(hi.x, hi.y), double(f.x));
    return glm::mix(top, bottom, double(f.y));
}

// Runs test/scene_texture.comp (with `defines`) on `queries` over `scene`; one result a query.
std::vector<glm::vec4> textureQueries(
    gpu::Context& context, const SceneGpu& scene,
    const std::vector<std::pair<std::string, std::string>>& defines,
    const std::vector<glm::vec4>& queries) {
    const auto n = static_cast<uint32_t>(queries.size());
    gpu::ComputePipeline pipe(context, "test/scene_texture.comp", defines);
    gpu::Buffer q = hostBuffer(context, n * 16, "queries");
    gpu::Buffer r = hostBuffer(context, n * 16, "results");
    q.upload(context, queries.data(), n * 16);
    scene.bind(pipe);
    pipe.bind("test_queries", q).bind("test_results", r).set("count", n);
    context.submitAndWait([&](const vk::raii::CommandBuffer& cmd) { pipe.dispatch(cmd, n); });
    return r.downloadAs<glm::vec4>(context);
}

}  // namespace

TEST_F(SceneGpuTest, TextureSamplingMatchesCpuBilinear) {
    const Scene scene = fullScene();
    const SceneGpu gpuScene(ctx(), scene);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> coord(-2.0f, 3.0f);
    std::vector<glm::vec4> queries;
    struct Expect {
        int texture;
        glm::vec2 uv;
        bool srgb;
    };
    std::vector<Expect> expects;
    for (int tex = 0; tex < 3; ++tex)
        for (int i = 0; i < 400; ++i) {
            const Texture& t = scene.textures[tex];
            glm::vec2 uv(coord(rng), coord(rng));
            if (i < 40)  // exact texel centres and texture edges
                uv = glm::vec2((float(i % t.width) + 0.5f) / t.width,
                               (float(i / t.width % t.height) + 0.5f) / t.height);
            else if (i < 48)
                uv = glm::vec2(float(i % 2), float(i / 2 % 2)) * (i < 44 ? 1.0f : 0.9999999f);
            const bool srgb = i % 2 == 0;
            glm::vec4 q(uv, 0.0f, srgb ? 1.0f : 0.0f);
            std::memcpy(&q.z, &tex, 4);
            queries.push_back(q);
            expects.push_back({tex, uv, srgb});
        }
    const auto n = static_cast<uint32_t>(queries.size());
    const auto results = textureQueries(ctx(), gpuScene, gpuScene.defines(), queries);
    for (uint32_t i = 0; i < n; ++i) {
        const Expect& e = expects[i];
        const glm::dvec4 ref = referenceSample(scene.textures[e.texture], e.uv, e.srgb);
        for (int k = 0; k < 4; ++k)
            ASSERT_NEAR(results[i][k], ref[k], 1e-4)
                << "texture " << e.texture << " uv (" << e.uv.x << ", " << e.uv.y << ") srgb "
                << e.srgb << " channel " << k;
    }
    // Material lookup multiplies the factors: baseColor * texture, roughness * texel.g.
    glm::vec4 mq(0.37f, 0.61f, 0.0f, 0.0f);
    const uint32_t materialIndex = 1;
    std::memcpy(&mq.z, &materialIndex, 4);
    const glm::vec4 m = textureQueries(ctx(), gpuScene, {{"MATERIAL_QUERY", "1"}}, {mq})[0];
    const glm::dvec4 base = referenceSample(scene.textures[0], {0.37f, 0.61f}, true);
    const glm::dvec4 mr = referenceSample(scene.textures[1], {0.37f, 0.61f}, false);
    EXPECT_NEAR(m.r, 0.5 * base.r, 1e-4);
    EXPECT_NEAR(m.g, 0.25 * base.g, 1e-4);
    EXPECT_NEAR(m.b, 1.0 * base.b, 1e-4);
    EXPECT_NEAR(m.a, 0.5 * mr.g, 1e-4);
}

// Texture views on the GPU against the CPU reference (TextureSampling.cpp): one texture read by
// four materials with different KHR_texture_transforms and samplers (every wrap mode, nearest and
// bilinear), 300 UVs each in [-2, 3]^2. Nearest lookups are compared away from texel edges,
// where float rounding may pick the neighbour.
TEST_F(SceneGpuTest, TextureViewsMatchTheCpuReference) {
    Scene scene = sceneFromMesh(closedBox(2));
    scene.textures = {makeTexture(5, 3, 1)};
    std::vector<TextureView> views(4);
    views[0].transform = {{0.25f, -0.5f}, 0.7f, {2.0f, 0.5f}};  // repeat, bilinear
    views[1].sampler = {TextureWrap::ClampToEdge, TextureWrap::ClampToEdge, true};
    views[2].sampler = {TextureWrap::MirroredRepeat, TextureWrap::MirroredRepeat, true};
    views[2].transform.rotation = -1.3f;
    views[3].sampler = {TextureWrap::MirroredRepeat, TextureWrap::ClampToEdge, false};
    views[3].transform.scale = {1.5f, 3.0f};
    scene.materials.clear();
    for (const TextureView& v : views) {
        Material m;
        m.baseColorTexture = 0;
        m.baseColorView = v;
        m.emissiveTexture = 0;  // the emissive slot reads through its own (identity) view
        scene.materials.push_back(m);
    }
    const SceneGpu gpuScene(ctx(), scene);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> coord(-2.0f, 3.0f);
    struct Expect {
        uint32_t material, slot;
        glm::vec2 uv;
    };
    std::vector<glm::vec4> queries;
    std::vector<Expect> expects;
    for (uint32_t m = 0; m < views.size(); ++m)
        for (int i = 0; i < 300; ++i) {
            const uint32_t slot = i % 10 == 0 ? 2u : 0u;
            const glm::vec2 uv(coord(rng), coord(rng));
            glm::vec4 q(uv, 0.0f, float(slot));
            std::memcpy(&q.z, &m, 4);
            queries.push_back(q);
            expects.push_back({m, slot, uv});
        }
    const auto n = static_cast<uint32_t>(queries.size());
    const auto results = textureQueries(ctx(), gpuScene, {{"VIEW_QUERY", "1"}}, queries);
    const Texture& t = scene.textures[0];
    int compared = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const Expect& e = expects[i];
        const TextureView& view =
            e.slot == 0 ? scene.materials[e.material].baseColorView : TextureView{};
        if (view.sampler.nearest) {
            const glm::vec2 st = view.transform.apply(e.uv) * glm::vec2(t.width, t.height);
            const glm::vec2 edge = glm::abs(st - glm::round(st));
            if (edge.x < 1e-3f || edge.y < 1e-3f) continue;
        }
        const glm::vec4 ref = sampleTexture(t, view, e.uv, true);
        ++compared;
        for (int k = 0; k < 4; ++k)
            ASSERT_NEAR(results[i][k], ref[k], 1e-4)
                << "material " << e.material << " slot " << e.slot << " uv (" << e.uv.x << ", "
                << e.uv.y << ") channel " << k;
    }
    EXPECT_GT(compared, 1100);
}

TEST_F(SceneGpuTest, LightSamplingMatchesTheTable) {
    // Seen from the origin: E1 faces it, E2 shows its back but is double-sided, E3 shows its
    // back and is one-sided (every sample invalid); plus point, spot and directional lights.
    Scene scene;
    scene.materials = {Material{}, emissiveMaterial({1, 1, 1}, false),
                       emissiveMaterial({0, 3, 0}, true), emissiveMaterial({5, 0, 0}, false)};
    addTriangle(scene.mesh, {-0.5f, -0.5f, 1}, {-0.5f, 0.5f, 1}, {0.5f, -0.5f, 1}, 1);  // E1
    addTriangle(scene.mesh, {2, -1, -1}, {2, 1, -1}, {2, -1, 1}, 2);                    // E2
    addTriangle(scene.mesh, {-1, -1.5f, -1}, {1, -1.5f, -1}, {-1, -1.5f, 1}, 3);        // E3
    addTriangle(scene.mesh, {-3, -3, -2}, {3, -3, -2}, {-3, 3, -2}, 0);                 // floor
    Light point;
    point.position = {0, 3, 0};
    point.intensity = 20.0f;
    Light spot;
    spot.type = Light::Type::Spot;
    spot.position = {1, 1, 1};
    spot.intensity = 8.0f;
    Light sun;
    sun.type = Light::Type::Directional;
    sun.direction = {0, 0, -1};
    sun.intensity = 0.5f;
    scene.lights = {point, spot, sun};
    const Bvh bvh(scene.mesh);
    const LightTable table(scene, bvh.triangleOrder());
    const SceneGpu gpuScene(ctx(), scene, bvh, table);
    ASSERT_EQ(table.entries().size(), 6u);

    const uint32_t n = 200000;
    gpu::ComputePipeline pipe(ctx(), "test/scene_lights.comp", gpuScene.defines());
    gpu::Buffer out = hostBuffer(ctx(), size_t(n) * 32, "samples");
    gpuScene.bind(pipe);
    pipe.bind("test_samples", out).set("position", glm::vec4(0.0f)).set("count", n);
    ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) { pipe.dispatch(cmd, n); });
    const auto samples = out.downloadAs<glm::vec4>(ctx());

    std::map<uint32_t, double> expectedPdf;
    for (const auto& e : table.entries()) expectedPdf[e.light] = e.pdf;
    std::map<uint32_t, uint32_t> counts, valid;
    const auto& order = bvh.triangleOrder();
    for (uint32_t i = 0; i < n; ++i) {
        const glm::vec4 a = samples[2 * i], b = samples[2 * i + 1];
        uint32_t light;
        std::memcpy(&light, &a.x, 4);
        ASSERT_TRUE(expectedPdf.count(light))
            << "sample " << i << " picked unknown light " << light;
        ++counts[light];
        if (a.w == 0.0f) continue;
        ++valid[light];
        ASSERT_GT(a.y, 0.0f);
        ASSERT_NEAR(glm::length(glm::vec3(b)), 1.0f, 1e-5f);
        if (light & kEmitterPunctualBit) {
            EXPECT_FLOAT_EQ(a.y, float(expectedPdf[light]));
            continue;
        }
        // The MIS pdf recomputed from the hit point equals the sampling pdf.
        ASSERT_NEAR(a.z, a.y, 2e-3f * a.y) << "sample " << i;
        if (order[light] == 0) {
            ASSERT_NEAR(b.z * b.w, 1.0f, 1e-4f);  // on E1's plane z = 1
        }
    }
    for (const auto& [light, pdf] : expectedPdf) {
        const double expected = n * pdf;
        EXPECT_NEAR(double(counts[light]), expected, 5.0 * std::sqrt(expected) + 1.0)
            << "light " << light;
    }
    // One-sided back faces never give a sample; the others always do.
    for (const auto& [light, count] : counts) {
        if (light & kEmitterPunctualBit) {
            EXPECT_EQ(valid[light], count);
            continue;
        }
        const uint32_t meshTri = order[light];
        EXPECT_EQ(valid[light], meshTri == 2 ? 0u : count) << "mesh triangle " << meshTri;
    }
}

#ifdef FOVEA_TEST_HAS_SCENE_LOADER
// Real scenes upload with the features they have; prints the memory per buffer.
TEST_F(SceneGpuTest, LoadedScenes) {
    struct Case {
        std::string spec;
        uint32_t features;
    };
    const std::filesystem::path helmet = std::filesystem::path(FOVEA_SOURCE_DIR) /
                                         "../shared/scenes/flight-helmet/FlightHelmet.gltf";
    std::vector<Case> cases = {{"builtin:cornell", graph::kSceneGeometry | graph::kSceneEmissive},
                               {"builtin:forest", graph::kSceneGeometry | graph::kScenePunctual}};
    if (std::filesystem::exists(helmet))
        cases.push_back({helmet.string(), graph::kSceneGeometry | graph::kSceneTextures});
    for (const Case& c : cases) {
        const Scene scene = loadScene(c.spec);
        const SceneGpu gpuScene(ctx(), scene);
        EXPECT_EQ(gpuScene.features() & c.features, c.features) << c.spec;
        std::cout << "[ SceneGpu ] " << c.spec << ": " << scene.mesh.triangles.size()
                  << " triangles, " << gpuScene.info().emitterCount << " lights, "
                  << gpuScene.totalBytes() / 1024 << " KiB:";
        for (const auto& [name, bytes] : gpuScene.memoryStats())
            std::cout << " " << name << "=" << bytes / 1024 << "K";
        std::cout << "\n";
    }
}
#endif

// Issue 28: a scene larger than the device binds per storage buffer is an error naming the buffer,
// its size and the device's limit, before any allocation; never a crash or a driver error.
TEST(SceneGpuLimits, SceneOverTheDeviceBufferLimitIsAClearError) {
    gpu::ContextOptions options;
    options.validation = true;
    // As a device binding 64 bytes per storage buffer: the geometry arrays then go by address
    // (SCENE_GEOMETRY_BY_ADDRESS), but the materials (64 bytes each) must be bound.
    options.storageBufferRangeCap = 64;
    gpu::Context small(options);
    EXPECT_EQ(small.limits().maxStorageBufferRange, 64u);
    const Scene cornell = loadScene("builtin:cornell");
    try {
        SceneGpu gpu(small, cornell);
        FAIL() << "uploaded";
    } catch (const RuntimeError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("binds at most 64 bytes per storage buffer"), std::string::npos)
            << what;
        EXPECT_NE(what.find("38 triangles"), std::string::npos) << what;
        EXPECT_NE(what.find("'scene_"), std::string::npos) << what;
    }
    EXPECT_TRUE(small.validationMessages().empty());
}
