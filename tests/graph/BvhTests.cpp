// BVH tests: CPU build invariants and degenerate input (BvhBuild), GPU closest-hit and occlusion
// queries against a brute-force CPU reference (BvhGpu).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <glm/glm.hpp>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

#include "core/scene/Bvh.h"
#include "core/scene/SceneGpu.h"
#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Context.h"
#include "core/vk/Resources.h"
#include "tests/graph/GpuTestFixture.h"
#include "tests/unit/SceneTestUtil.h"

#if __has_include("core/scene/SceneLoader.h")
#include "core/scene/SceneLoader.h"
#define FOVEA_TEST_HAS_SCENE_LOADER 1
#endif

using namespace fovea;
using namespace fovea::scene;
using namespace fovea::test;

namespace {

bool contains(const glm::vec3& outerMin, const glm::vec3& outerMax, const glm::vec3& innerMin,
              const glm::vec3& innerMax) {
    return glm::all(glm::lessThanEqual(outerMin, innerMin)) &&
           glm::all(glm::greaterThanEqual(outerMax, innerMax));
}

bool finiteVec(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Every structural promise of Bvh: a permutation order, each valid triangle in exactly one leaf,
// children inside parents, leaves containing their triangles, leaf size and depth limits.
void checkInvariants(const TriangleMesh& mesh, const Bvh& bvh, uint32_t maxLeaf = 4) {
    const auto& nodes = bvh.nodes();
    const auto& order = bvh.triangleOrder();
    ASSERT_FALSE(nodes.empty());
    ASSERT_EQ(order.size(), mesh.triangles.size());
    std::vector<uint32_t> seenInOrder(mesh.triangles.size(), 0);
    for (uint32_t t : order) {
        ASSERT_LT(t, mesh.triangles.size());
        ++seenInOrder[t];
    }
    for (uint32_t c : seenInOrder) ASSERT_EQ(c, 1u) << "triangleOrder is not a permutation";

    const uint32_t valid = bvh.stats().triangleCount - bvh.stats().invalidTriangles;
    std::vector<uint32_t> inLeaf(order.size(), 0);
    struct Item {
        uint32_t node, depth;
    };
    std::vector<Item> stack{{0, 0}};
    uint32_t visited = 0, maxDepth = 0;
    while (!stack.empty()) {
        const Item item = stack.back();
        stack.pop_back();
        ++visited;
        ASSERT_LT(item.node, nodes.size());
        const BvhNode& node = nodes[item.node];
        maxDepth = std::max(maxDepth, item.depth);
        ASSERT_LE(item.depth, Bvh::kMaxDepth);
        if (node.isLeaf()) {
            ASSERT_LE(node.count, maxLeaf);
            ASSERT_LE(node.index + node.count, valid) << "leaf reaches the invalid triangles";
            for (uint32_t i = node.index; i < node.index + node.count; ++i) {
                ++inLeaf[i];
                const glm::uvec3 tri = mesh.triangles[order[i]];
                for (int k = 0; k < 3; ++k) {
                    const glm::vec3 p = mesh.positions[tri[k]];
                    ASSERT_TRUE(contains(node.boundsMin, node.boundsMax, p, p))
                        << "leaf " << item.node << " misses a vertex of triangle " << order[i];
                }
            }
        } else {
            ASSERT_TRUE(finiteVec(node.boundsMin) && finiteVec(node.boundsMax));
            const uint32_t left = item.node + 1, right = node.index;
            ASSERT_LT(left, nodes.size());
            ASSERT_LT(right, nodes.size());
            ASSERT_GT(right, left);
            for (uint32_t child : {left, right})
                ASSERT_TRUE(contains(node.boundsMin, node.boundsMax, nodes[child].boundsMin,
                                     nodes[child].boundsMax))
                    << "child " << child << " outside parent " << item.node;
            stack.push_back({left, item.depth + 1});
            stack.push_back({right, item.depth + 1});
        }
    }
    EXPECT_EQ(visited, nodes.size()) << "unreachable nodes";
    EXPECT_EQ(maxDepth, bvh.stats().maxDepth);
    for (uint32_t i = 0; i < order.size(); ++i)
        ASSERT_EQ(inLeaf[i], i < valid ? 1u : 0u) << "triangle slot " << i;
}

}  // namespace

// --- CPU build --------------------------------------------------------------------------------

TEST(BvhBuild, InvariantsOnProceduralMeshes) {
    for (const auto& mesh : {triangleSoup(5000, 1), gridMesh(40), closedBox(6)}) {
        Bvh bvh(mesh);
        checkInvariants(mesh, bvh);
        EXPECT_EQ(bvh.stats().invalidTriangles, 0u);
        EXPECT_GT(bvh.stats().leafCount, mesh.triangles.size() / 4 - 1);
        EXPECT_GT(bvh.stats().sahCost, 0.0);
    }
}

TEST(BvhBuild, OptionsAreHonoured) {
    const TriangleMesh mesh = triangleSoup(3000, 2);
    for (uint32_t leaf : {1u, 2u, 8u}) {
        Bvh bvh(mesh, BvhBuildOptions{.bins = 8, .maxLeafSize = leaf});
        checkInvariants(mesh, bvh, leaf);
    }
}

TEST(BvhBuild, EmptyAndSingleTriangle) {
    TriangleMesh empty;
    Bvh e(empty);
    ASSERT_EQ(e.nodes().size(), 1u);
    EXPECT_TRUE(e.nodes()[0].isLeaf());
    EXPECT_EQ(e.nodes()[0].count, 0u);
    EXPECT_TRUE(e.bounds().empty());

    TriangleMesh one;
    addTriangle(one, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    Bvh b(one);
    ASSERT_EQ(b.nodes().size(), 1u);
    EXPECT_EQ(b.nodes()[0].count, 1u);
    checkInvariants(one, b);
}

TEST(BvhBuild, DegenerateInputs) {
    // All triangles coincident: no SAH plane exists, median splits must still terminate.
    TriangleMesh same;
    for (int i = 0; i < 1000; ++i) addTriangle(same, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    // Zero-area triangles: points and segments, some coincident.
    TriangleMesh zero;
    for (int i = 0; i < 500; ++i) {
        const glm::vec3 p(float(i % 7), 0.0f, 0.0f);
        addTriangle(zero, p, p, p);
        addTriangle(zero, p, p + glm::vec3(1, 0, 0), p + glm::vec3(2, 0, 0));
    }
    // Huge and tiny coordinates together (float areas would overflow).
    TriangleMesh huge;
    for (int i = 0; i < 300; ++i) {
        const float s = (i % 3 == 0) ? 1e30f : (i % 3 == 1 ? 1e-30f : 1.0f);
        const float o = float(i) * s * 0.01f;
        addTriangle(huge, {o, -s, 0}, {o + s, s, 0}, {o, 0, s});
    }
    addTriangle(huge, {-3e38f, -3e38f, -3e38f}, {3e38f, 3e38f, 3e38f}, {3e38f, -3e38f, 0});
    // Geometric sizes: a naive SAH would chain one triangle per level.
    TriangleMesh chain;
    for (int i = 0; i < 2000; ++i) {
        const float s = std::pow(1.02f, float(i));
        addTriangle(chain, {s, 0, 0}, {s * 1.01f, 0, 0}, {s, 0.01f * s, 0});
    }
    for (const TriangleMesh* mesh : {&same, &zero, &huge, &chain}) {
        Bvh bvh(*mesh);
        checkInvariants(*mesh, bvh);
        EXPECT_LE(bvh.stats().maxDepth, Bvh::kMaxDepth);
        EXPECT_TRUE(std::isfinite(bvh.stats().sahCost));
        EXPECT_EQ(bvh.stats().invalidTriangles, 0u);
    }
}

TEST(BvhBuild, NonFiniteTrianglesAreLeftOut) {
    TriangleMesh mesh = triangleSoup(200, 3);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    addTriangle(mesh, {nan, 0, 0}, {1, 0, 0}, {0, 1, 0});
    addTriangle(mesh, {0, 0, 0}, {inf, 0, 0}, {0, 1, 0});
    Bvh bvh(mesh);
    EXPECT_EQ(bvh.stats().invalidTriangles, 2u);
    checkInvariants(mesh, bvh);
    EXPECT_TRUE(finiteVec(bvh.bounds().min) && finiteVec(bvh.bounds().max));
}

TEST(BvhBuild, BadIndexThrows) {
    TriangleMesh mesh;
    mesh.positions = {glm::vec3(0.0f), glm::vec3(1.0f)};
    mesh.triangles = {glm::uvec3(0, 1, 2)};
    mesh.materialIds = {0};
    try {
        Bvh bvh(mesh);
        FAIL() << "expected RuntimeError";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("vertex 2"), std::string::npos) << e.what();
    }
}

TEST(BvhBuild, ValidFor200kTriangles) {
    const TriangleMesh mesh = triangleSoup(200000, 4, 10.0f, 0.1f);
    Bvh bvh(mesh);
    const BvhStats& s = bvh.stats();
    std::cout << "[ BvhBuild ] 200k triangles: " << s.nodeCount << " nodes, " << s.leafCount
              << " leaves (avg " << s.averageLeafTriangles << ", max " << s.maxLeafTriangles
              << "), depth " << s.maxDepth << ", SAH " << s.sahCost << ", " << s.buildMs << " ms\n";
    checkInvariants(mesh, bvh);
    // Build time is printed here and reported as build_ms in report.json; it is measured by
    // benchmarks, never asserted (a loaded CI machine would fail a timed test).
}

// --- GPU queries ------------------------------------------------------------------------------

namespace {

struct TestRay {
    glm::vec4 originTMin;
    glm::vec4 directionTMax;
};

struct QueryResult {
    std::vector<glm::vec4> hits;
    std::vector<uint32_t> occluded;
};

QueryResult runQueries(gpu::Context& ctx, const SceneGpu& scene, const std::vector<TestRay>& rays,
                       const gpu::ShaderDefines& defines) {
    gpu::ComputePipeline pipe(ctx, "test/bvh_query.comp", defines);
    const auto n = static_cast<uint32_t>(rays.size());
    gpu::Buffer rayBuffer(
        ctx, rays.size() * sizeof(TestRay),
        vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferDst, false,
        "rays");
    gpu::Buffer hitBuffer(
        ctx, rays.size() * 16,
        vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferSrc, false,
        "hits");
    gpu::Buffer occBuffer(
        ctx, rays.size() * 4,
        vk::BufferUsageFlagBits::eStorageBuffer | vk::BufferUsageFlagBits::eTransferSrc, false,
        "occluded");
    rayBuffer.upload(ctx, rays.data(), rays.size() * sizeof(TestRay));
    scene.bind(pipe);
    pipe.bind("test_rays", rayBuffer)
        .bind("test_hits", hitBuffer)
        .bind("test_occlusion", occBuffer)
        .set("count", n);
    ctx.submitAndWait([&](const vk::raii::CommandBuffer& cmd) { pipe.dispatch(cmd, n); });
    return {hitBuffer.downloadAs<glm::vec4>(ctx), occBuffer.downloadAs<uint32_t>(ctx)};
}

// Random rays around `bounds`: origins in the box grown by 50% (or inside it), directions
// random, aimed at a random point in the box, or axis-aligned (zero components), with a mix of
// tMin/tMax limits.
std::vector<TestRay> makeRays(const Bounds& bounds, uint32_t count, uint32_t seed, bool inside) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const glm::vec3 centre = bounds.center(), half = 0.5f * bounds.extent();
    const float scale = glm::length(bounds.extent());
    auto pointIn = [&](float grow) {
        return centre +
               grow * half * glm::vec3(2 * unit(rng) - 1, 2 * unit(rng) - 1, 2 * unit(rng) - 1);
    };
    std::vector<TestRay> rays(count);
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 o = inside ? pointIn(0.95f) : pointIn(1.5f);
        glm::vec3 d;
        const uint32_t kind = i % 10;
        if (kind < 4) {
            d = glm::vec3(2 * unit(rng) - 1, 2 * unit(rng) - 1, 2 * unit(rng) - 1);
        } else if (kind < 9) {
            d = pointIn(1.0f) - o;
        } else {
            d = glm::vec3(0.0f);
            d[i % 3] = (i % 2) ? 1.0f : -1.0f;
        }
        if (glm::length(d) == 0.0f) d = glm::vec3(0, 0, 1);
        if (i % 3 == 0) d = glm::normalize(d);
        float tMin = 0.0f, tMax = 1e30f;
        // From inside a closed box every unlimited ray hits; limits would make misses legal.
        if (!inside && i % 4 == 1) tMin = unit(rng) * 0.3f * scale / glm::length(d);
        if (!inside && i % 4 == 2) tMax = unit(rng) * 1.5f * scale / glm::length(d);
        rays[i] = {glm::vec4(o, tMin), glm::vec4(d, tMax)};
    }
    return rays;
}

bool nearEdge(const glm::vec2& bary) {
    const float w0 = 1.0f - bary.x - bary.y;
    return std::min({bary.x, bary.y, w0}) < 1e-4f;
}

bool relClose(float a, float b, float rel = 1e-4f) {
    return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)) + 1e-30f;
}

struct Agreement {
    uint32_t hits = 0, edgeDisagreements = 0, occludedCount = 0, ambiguousOcclusion = 0;
};

// Compares GPU results with brute force; fails on any disagreement a rounding difference on a
// shared edge cannot explain.
// One brute-force pass per ray: the closest hit in (tMin, tMax) and whether anything occludes
// it. Hits within 1e-4 of either end or on an edge make the occlusion answer ambiguous under
// rounding.
struct Reference {
    CpuHit closest;
    bool occluded = false, ambiguous = false;
};

Reference bruteForce(const TriangleMesh& mesh, const glm::vec3& o, const glm::vec3& d, float tMin,
                     float tMax) {
    Reference r;
    r.closest.t = tMax;
    for (uint32_t tri = 0; tri < mesh.triangles.size(); ++tri) {
        float t;
        glm::vec2 bary;
        // Same as testing (tMin, tMax) directly: the range check is a final comparison on t.
        if (!intersectMeshTriangle(mesh, tri, o, d, 0.0f, 1e30f, t, bary)) continue;
        if (t > tMin && t < r.closest.t) r.closest = {true, t, tri, bary};
        if (relClose(t, tMax) || relClose(t, tMin) || nearEdge(bary))
            r.ambiguous = r.ambiguous || (t > tMin * 0.999f && t < tMax * 1.001f);
        else if (t > tMin && t < tMax)
            r.occluded = true;
    }
    return r;
}

// Compares GPU results with brute force; fails on any disagreement a rounding difference on a
// shared edge cannot explain.
Agreement compareWithBruteForce(const TriangleMesh& mesh, const SceneGpu& scene,
                                const std::vector<TestRay>& rays, const QueryResult& result,
                                const std::string& label) {
    Agreement a;
    const auto& order = scene.triangleOrder();
    uint32_t failures = 0;
    for (size_t i = 0; i < rays.size() && failures < 10; ++i) {
        const glm::vec3 o(rays[i].originTMin), d(rays[i].directionTMax);
        const float tMin = rays[i].originTMin.w, tMax = rays[i].directionTMax.w;
        const Reference ref = bruteForce(mesh, o, d, tMin, tMax);
        const CpuHit& cpu = ref.closest;
        SCOPED_TRACE(label + " ray " + std::to_string(i));

        if (ref.occluded) ++a.occludedCount;
        if (ref.ambiguous && !ref.occluded) {
            ++a.ambiguousOcclusion;
        } else if ((result.occluded[i] != 0) != ref.occluded) {
            ADD_FAILURE() << "occlusion cpu " << ref.occluded << " gpu " << result.occluded[i];
            ++failures;
        }

        const glm::vec4 g = result.hits[i];
        uint32_t gpuTri;
        std::memcpy(&gpuTri, &g.y, 4);
        const bool gpuHit = gpuTri != 0xFFFFFFFFu;
        if (cpu.hit) ++a.hits;
        if (cpu.hit != gpuHit) {
            // Only a ray through a shared edge/vertex may flip with FMA-level rounding.
            const glm::vec2 gpuBary(g.z, g.w);
            if ((cpu.hit && nearEdge(cpu.bary)) || (gpuHit && nearEdge(gpuBary))) {
                ++a.edgeDisagreements;
            } else {
                ADD_FAILURE() << "cpu hit " << cpu.hit << " (t " << cpu.t << ") vs gpu hit "
                              << gpuHit << " (t " << g.x << ")";
                ++failures;
            }
            continue;
        }
        if (!cpu.hit) continue;
        if (gpuTri >= order.size()) {
            ADD_FAILURE() << "gpu triangle id " << gpuTri << " out of range";
            ++failures;
            continue;
        }
        const uint32_t meshTri = order[gpuTri];
        if (meshTri != cpu.triangle) {
            // A tie: the GPU's triangle must be hit at the same distance.
            float t;
            glm::vec2 bary;
            const bool hitsToo = intersectMeshTriangle(mesh, meshTri, o, d, tMin, 1e30f, t, bary);
            if (!hitsToo || !relClose(t, cpu.t)) {
                if (nearEdge(cpu.bary)) {
                    ++a.edgeDisagreements;
                    continue;
                }
                ADD_FAILURE() << "gpu triangle " << meshTri << " (t " << g.x << ") vs cpu "
                              << cpu.triangle << " (t " << cpu.t << ")";
                ++failures;
                continue;
            }
        }
        if (!relClose(g.x, cpu.t)) {
            ADD_FAILURE() << "t gpu " << g.x << " cpu " << cpu.t;
            ++failures;
        }
    }
    return a;
}

void checkScene(gpu::Context& ctx, const Scene& scene, const std::string& label, bool inside,
                uint32_t rayCount = 10000) {
    const SceneGpu gpuScene(ctx, scene);
    Bounds bounds;
    for (const auto& p : scene.mesh.positions) bounds.grow(p);
    if (bounds.empty()) {
        bounds.grow(glm::vec3(-1.0f));
        bounds.grow(glm::vec3(1.0f));
    }
    const auto rays = makeRays(bounds, rayCount, 1234, inside);
    const auto start = std::chrono::steady_clock::now();
    // Geometry only: the brute force knows no alpha, so FlightHelmet's BLEND lenses are traced
    // opaque here (the alpha test has its own tests, tests/graph/AlphaMaskTests.cpp).
    gpu::ShaderDefines defines = gpuScene.defines();
    for (auto& [name, value] : defines)
        if (name == "SCENE_HAS_ALPHA") value = "0";
    const QueryResult result = runQueries(ctx, gpuScene, rays, defines);
    const double gpuMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const Agreement a = compareWithBruteForce(scene.mesh, gpuScene, rays, result, label);
    const BvhStats& s = gpuScene.bvhStats();
    std::cout << "[ BvhGpu ] " << label << ": " << scene.mesh.triangles.size() << " triangles, "
              << s.nodeCount << " nodes, depth " << s.maxDepth << ", build " << s.buildMs << " ms; "
              << rays.size() << " rays, " << a.hits << " hits, " << a.occludedCount << " occluded, "
              << a.edgeDisagreements << " edge flips, " << a.ambiguousOcclusion
              << " ambiguous; GPU " << gpuMs << " ms\n";
    EXPECT_LE(a.edgeDisagreements, rays.size() / 1000) << label;
    if (inside) {
        EXPECT_EQ(a.hits, rays.size()) << label << ": rays from inside a closed box";
    }
}

class BvhGpu : public GpuTest {};

}  // namespace

TEST_F(BvhGpu, TriangleSoupMatchesBruteForce) {
    checkScene(ctx(), sceneFromMesh(triangleSoup(4000, 11)), "soup-4k", false);
}

// Issue 28: geometry larger than a storage descriptor binds (here a device capped at 16 KiB;
// lavapipe's 128 MiB for a 10M-triangle scene) is read through device addresses, with the same
// hits as the brute force.
TEST_F(BvhGpu, GeometryReadThroughDeviceAddressesMatchesBruteForce) {
    gpu::ContextOptions options;
    options.validation = true;
    options.storageBufferRangeCap = 16384;
    gpu::Context small(options);
    const Scene soup = sceneFromMesh(triangleSoup(4000, 11));  // 192 KB of intersection data
    {
        const SceneGpu probe(small, soup);
        bool byAddress = false;
        for (const auto& [name, value] : probe.defines())
            if (name == "SCENE_GEOMETRY_BY_ADDRESS") byAddress = value == "1";
        EXPECT_TRUE(byAddress);
        EXPECT_NE(probe.info().nodeAddress, 0u);
    }
    checkScene(small, soup, "soup-4k by address", false);
    EXPECT_TRUE(small.validationMessages().empty());
    // Small enough to bind: the descriptor path (faster on lavapipe), no addresses.
    const SceneGpu bound(ctx(), soup);
    EXPECT_EQ(bound.info().nodeAddress, 0u);
}

TEST_F(BvhGpu, LargeSoupMatchesBruteForce) {
    checkScene(ctx(), sceneFromMesh(triangleSoup(20000, 12, 4.0f, 0.3f)), "soup-20k", false);
}

TEST_F(BvhGpu, GridMatchesBruteForce) {
    checkScene(ctx(), sceneFromMesh(gridMesh(64)), "grid-64", false);
}

TEST_F(BvhGpu, ClosedBoxAlwaysHitFromInside) {
    checkScene(ctx(), sceneFromMesh(closedBox(10)), "box-10", true);
}

TEST_F(BvhGpu, CoincidentTrianglesTie) {
    TriangleMesh mesh = triangleSoup(300, 13);
    for (int i = 0; i < 50; ++i) addTriangle(mesh, {-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
    checkScene(ctx(), sceneFromMesh(std::move(mesh)), "coincident", false, 4000);
}

TEST_F(BvhGpu, EmptySceneMisses) {
    Scene scene = sceneFromMesh(TriangleMesh{});
    const SceneGpu gpuScene(ctx(), scene);
    Bounds bounds;
    bounds.grow(glm::vec3(-1.0f));
    bounds.grow(glm::vec3(1.0f));
    const auto rays = makeRays(bounds, 256, 5, false);
    const QueryResult r = runQueries(ctx(), gpuScene, rays, gpuScene.defines());
    for (size_t i = 0; i < rays.size(); ++i) {
        uint32_t tri;
        std::memcpy(&tri, &r.hits[i].y, 4);
        EXPECT_EQ(tri, 0xFFFFFFFFu);
        EXPECT_EQ(r.occluded[i], 0u);
    }
}

#ifdef FOVEA_TEST_HAS_SCENE_LOADER
TEST_F(BvhGpu, BuiltinCornellMatchesBruteForce) {
    const Scene scene = loadScene("builtin:cornell");
    checkScene(ctx(), scene, "builtin:cornell", false);
}

// The heavy procedural scene (~200k triangles): fewer rays keep the brute force affordable.
TEST_F(BvhGpu, BuiltinForestMatchesBruteForce) {
    const Scene scene = loadScene("builtin:forest");
    Bvh bvh(scene.mesh);
    checkInvariants(scene.mesh, bvh);
    checkScene(ctx(), scene, "builtin:forest", false, 1000);
}

TEST_F(BvhGpu, FlightHelmetMatchesBruteForce) {
    const std::filesystem::path file = std::filesystem::path(FOVEA_SOURCE_DIR) /
                                       "../shared/scenes/flight-helmet/FlightHelmet.gltf";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " not found";
    const Scene scene = loadScene(file.string());
    checkScene(ctx(), scene, "flight-helmet", false, 4000);
}
#endif
