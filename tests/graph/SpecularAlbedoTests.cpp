// Pre-integrated specular reflectance (core/shading/SpecularAlbedo.h, issue 26): the VNDF
// integration against an independent quadrature of the BRDF formula, the smooth-mirror limit,
// the generated shader table against the integration (FOVEA_UPDATE_TABLES=1 rewrites it), the
// bilinear lookup's error off the grid, and the shader lookup against the CPU one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "core/shading/SpecularAlbedo.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::shading;
namespace fs = std::filesystem;

namespace {

const fs::path kTableFile =
    fs::path(FOVEA_SOURCE_DIR) / "core" / "shading" / "SpecularAlbedoTable.inc";

const std::vector<glm::vec2>& table() {
    return bakedSpecularAlbedoTable();
}

TEST(SpecularAlbedo, VndfIntegrationMatchesQuadratureOfTheBrdf) {
    for (double roughness : {0.3, 0.5, 0.75, 1.0})
        for (double nov : {0.05, 0.2, 0.5, 0.8, 1.0}) {
            const glm::dvec2 v = integrateSpecularAlbedo(nov, roughness);
            const glm::dvec2 q = integrateSpecularAlbedoQuadrature(nov, roughness, 1024, 512);
            // At grazing view the lobe narrows onto a few quadrature cells: looser there.
            const double tol = nov < 0.1 ? 1.5e-2 : 2e-3;
            EXPECT_NEAR(v.x, q.x, tol) << "scale at NoV " << nov << " roughness " << roughness;
            EXPECT_NEAR(v.y, q.y, tol) << "bias at NoV " << nov << " roughness " << roughness;
            EXPECT_LE(v.x + v.y, 1.0 + 1e-6) << "F0 = 1 reflects more than it receives";
        }
}

TEST(SpecularAlbedo, SmoothMirrorReflectsSchlickFresnel) {
    // alpha at its floor (2e-3): every visible normal is the surface normal, G2 / G1 = 1, so the
    // lobe reflects F(NoV) = F0 + (1 - F0)(1 - NoV)^5 of the light.
    for (double nov : {0.1, 0.3, 0.6, 1.0}) {
        const glm::dvec2 t = integrateSpecularAlbedo(nov, 0.0, 32);
        EXPECT_NEAR(t.x + t.y, 1.0, 2e-3) << nov;
        EXPECT_NEAR(t.y, std::pow(1.0 - nov, 5.0), 2e-3) << nov;
    }
    // Rough surfaces lose energy (single scattering). At roughness 1 (alpha 1) and NoV 1, D =
    // 1/pi and G2 = 1 / (1 + Lambda(l)) with Lambda(l) = (1/l - 1) / 2, so E(F0 = 1) =
    // integral over l of l / (1 + l) = 1 - ln 2 exactly.
    const glm::dvec2 rough = integrateSpecularAlbedo(1.0, 1.0);
    EXPECT_NEAR(rough.x + rough.y, 1.0 - std::log(2.0), 1e-3);
}

TEST(SpecularAlbedo, BakedTableMatchesTheIntegration) {
    const std::vector<glm::vec2> integrated = specularAlbedoTable();
    const std::string expected = specularAlbedoTableSource(integrated);
    if (std::getenv("FOVEA_UPDATE_TABLES")) {
        std::ofstream(kTableFile, std::ios::binary) << expected;
        GTEST_SKIP() << "rewrote " << kTableFile << "; rebuild to bake it";
    }
    std::ifstream in(kTableFile, std::ios::binary);
    ASSERT_TRUE(in) << kTableFile;
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_TRUE(text.str() == expected)
        << kTableFile << " is out of date: FOVEA_UPDATE_TABLES=1 build/tests/fovea_tests "
        << "--gtest_filter='SpecularAlbedo.*' rewrites it";
    ASSERT_EQ(table().size(), integrated.size());
    for (size_t k = 0; k < integrated.size(); ++k) {
        EXPECT_NEAR(table()[k].x, integrated[k].x, 1e-7) << "entry " << k;
        EXPECT_NEAR(table()[k].y, integrated[k].y, 1e-7) << "entry " << k;
    }
}

TEST(SpecularAlbedo, BilinearLookupStaysCloseToTheIntegralOffTheGrid) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double worst = 0.0, sum = 0.0;
    const int n = 400;
    for (int k = 0; k < n; ++k) {
        const double nov = u(rng), roughness = u(rng);
        const glm::dvec2 exact = integrateSpecularAlbedo(nov, roughness, 64);
        const glm::dvec2 look = lookupSpecularAlbedo(table(), nov, roughness);
        // The error of E for the worst F0 (0 or 1) of this point.
        const double e =
            std::max(std::abs(look.y - exact.y), std::abs(look.x + look.y - exact.x - exact.y));
        worst = std::max(worst, e);
        sum += e;
    }
    std::printf("specular albedo lookup: max |error| %.5f, mean %.5f over %d random points\n",
                worst, sum / n, n);
    EXPECT_LT(worst, 0.02);
    EXPECT_LT(sum / n, 0.002);
}

class SpecularAlbedoGpu : public GpuTest {};

TEST_F(SpecularAlbedoGpu, ShaderLookupMatchesTheCpuLookup) {
    std::vector<glm::vec2> queries;
    std::mt19937 rng(9);
    std::uniform_real_distribution<float> u(-0.2f, 1.2f);  // out of range clamps
    for (int k = 0; k < 500; ++k) queries.emplace_back(u(rng), u(rng));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    queries.emplace_back(nan, 0.5f);
    queries.emplace_back(0.5f, nan);
    queries.emplace_back(1.0f, 1.0f);
    queries.emplace_back(0.0f, 0.0f);
    const auto n = uint32_t(queries.size());
    const auto usage = vk::BufferUsageFlagBits::eStorageBuffer |
                       vk::BufferUsageFlagBits::eTransferSrc |
                       vk::BufferUsageFlagBits::eTransferDst;
    gpu::Buffer q(ctx(), n * 8, usage, false, "queries");
    gpu::Buffer r(ctx(), n * 8, usage, false, "results");
    q.upload(ctx(), queries.data(), n * 8);
    gpu::Buffer t(ctx(), table().size() * 8, usage, false, "specular_albedo_table");
    t.upload(ctx(), table().data(), table().size() * 8);
    gpu::ComputePipeline pipe(ctx(), "test/specular_albedo.comp");
    pipe.bind("test_queries", q).bind("test_results", r).bind("specular_albedo_table", t);
    pipe.set("count", n);
    ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) { pipe.dispatch(cmd, n); });
    const auto results = r.downloadAs<glm::vec2>(ctx());
    for (uint32_t i = 0; i < n; ++i) {
        const glm::dvec2 cpu = lookupSpecularAlbedo(table(), queries[i].x, queries[i].y);
        EXPECT_NEAR(results[i].x, cpu.x, 1e-5) << "query " << i;
        EXPECT_NEAR(results[i].y, cpu.y, 1e-5) << "query " << i;
    }
}

}  // namespace
