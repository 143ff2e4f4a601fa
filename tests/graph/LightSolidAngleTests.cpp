// Light sampling by solid angle (shaders/common/scene_sample.glsl, SCENE_LIGHT_SOLID_ANGLE 1,
// PathTrace's lightSampling = solidAngle; Arvo 1995) against area sampling (the default), both
// through the test shader shaders/test/scene_lights.comp: every sample lies on the triangle it
// names, the MIS pdf sceneEmitterPdf recomputes equals the sampling pdf, and the Monte Carlo
// estimates of each triangle's solid angle and of its vector integral of directions
// (int omega d omega, Lambert's polygon formula) match the closed forms. A direction density that
// is not uniform in the solid angle, or a pdf that does not describe it, fails the last check.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <glm/glm.hpp>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/scene/Bvh.h"
#include "core/scene/LightTable.h"
#include "core/scene/SceneGpu.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"
#include "tests/graph/GpuTestFixture.h"
#include "tests/unit/SceneTestUtil.h"

using namespace fovea;
using namespace fovea::scene;

namespace {

using Corners = std::array<glm::dvec3, 3>;

// Solid angle of a triangle seen from the origin (Van Oosterom and Strackee 1983).
double solidAngle(const Corners& c) {
    const glm::dvec3 &a = c[0], &b = c[1], &d = c[2];
    const double la = glm::length(a), lb = glm::length(b), ld = glm::length(d);
    const double num = std::abs(glm::dot(a, glm::cross(b, d)));
    const double den =
        la * lb * ld + glm::dot(a, b) * ld + glm::dot(a, d) * lb + glm::dot(b, d) * la;
    return 2.0 * std::atan2(num, den);
}

// int_triangle omega d omega = 1/2 sum over edges of (arc angle) x (unit normal of the edge's
// great circle), oriented towards the triangle (Lambert's formula for the vector irradiance).
glm::dvec3 directionIntegral(const Corners& c) {
    glm::dvec3 v(0.0);
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3 a = glm::normalize(c[i]), b = glm::normalize(c[(i + 1) % 3]);
        v += 0.5 * std::acos(glm::clamp(glm::dot(a, b), -1.0, 1.0)) *
             glm::normalize(glm::cross(a, b));
    }
    const glm::dvec3 centre = (c[0] + c[1] + c[2]) / 3.0;
    return glm::dot(v, centre) < 0.0 ? -v : v;
}

class LightSolidAngleTest : public GpuTest {};

// Three double-sided emitters around the origin: a near large one (about 1.6 sr), a tilted one
// at distance 2, and a far tiny one below kSceneMinSolidAngle (area sampling in both modes).
TEST_F(LightSolidAngleTest, SamplesLieOnTheirTriangleAndIntegrateTheSolidAngle) {
    const std::vector<Corners> tris = {
        Corners{glm::dvec3(-1, -1, 0.5), glm::dvec3(1, -1, 0.5), glm::dvec3(0, 1, 0.5)},
        Corners{glm::dvec3(2, -0.5, -0.5), glm::dvec3(2.3, 0.5, -0.5), glm::dvec3(1.8, -0.5, 0.6)},
        Corners{glm::dvec3(-0.1, -20, 0), glm::dvec3(0.1, -20, 0), glm::dvec3(0, -20, 0.15)}};
    Scene scene;
    Material emitter;
    emitter.emissive = glm::vec3(1.0f);
    emitter.doubleSided = true;
    scene.materials = {emitter};
    for (const Corners& c : tris) test::addTriangle(scene.mesh, c[0], c[1], c[2], 0);
    const Bvh bvh(scene.mesh);
    const LightTable table(scene, bvh.triangleOrder());
    const SceneGpu gpuScene(ctx(), scene, bvh, table);
    ASSERT_EQ(table.entries().size(), 3u);
    ASSERT_LT(solidAngle(tris[2]), 3e-4);  // the fallback case
    const auto& order = bvh.triangleOrder();
    std::map<uint32_t, double> selection;  // GPU triangle index -> selection probability
    for (const auto& e : table.entries()) selection[e.light] = e.pdf;

    const uint32_t n = 100000;
    for (bool solid : {false, true}) {
        auto defines = gpuScene.defines();
        defines.emplace_back("SCENE_LIGHT_SOLID_ANGLE", solid ? "1" : "0");
        gpu::ComputePipeline pipe(ctx(), "test/scene_lights.comp", defines);
        gpu::Buffer out(ctx(), size_t(n) * 32,
                        vk::BufferUsageFlagBits::eStorageBuffer |
                            vk::BufferUsageFlagBits::eTransferSrc |
                            vk::BufferUsageFlagBits::eTransferDst,
                        false, "samples");
        gpuScene.bind(pipe);
        pipe.bind("test_samples", out).set("position", glm::vec4(0.0f)).set("count", n);
        ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) { pipe.dispatch(cmd, n); });
        const auto samples = out.downloadAs<glm::vec4>(ctx());

        // Per triangle: sums of 1/pdf and dir/pdf over its samples, and their squares.
        std::map<uint32_t, std::pair<glm::dvec4, glm::dvec4>> sums;
        for (uint32_t i = 0; i < n; ++i) {
            const glm::vec4 a = samples[2 * i], b = samples[2 * i + 1];
            uint32_t light;
            std::memcpy(&light, &a.x, 4);
            ASSERT_LT(light, 3u);
            ASSERT_EQ(a.w, 1.0f) << "double-sided emitters always give a sample";
            ASSERT_GT(a.y, 0.0f);
            ASSERT_NEAR(a.z, a.y, 2e-3f * a.y) << "MIS pdf, sample " << i << " solid " << solid;
            // The point lies in the plane of its triangle and inside it.
            const Corners& c = tris[order[light]];
            const glm::dvec3 p = glm::dvec3(glm::vec3(b)) * double(b.w);
            const glm::dvec3 e1 = c[1] - c[0], e2 = c[2] - c[0], q = p - c[0];
            const glm::dvec3 nrm = glm::normalize(glm::cross(e1, e2));
            ASSERT_NEAR(glm::dot(q, nrm), 0.0, 1e-4 * glm::length(p)) << "sample " << i;
            const double d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
            const double det = d00 * d11 - d01 * d01;
            const double b1 = (d11 * glm::dot(q, e1) - d01 * glm::dot(q, e2)) / det;
            const double b2 = (d00 * glm::dot(q, e2) - d01 * glm::dot(q, e1)) / det;
            const double outside = std::max({-b1, -b2, b1 + b2 - 1.0});
            ASSERT_LT(outside, 1e-5) << "sample " << i << " off its triangle " << order[light]
                                     << ": barycentrics " << b1 << ", " << b2;
            if (solid && order[light] < 2) {
                // Uniform in the solid angle: pdf = selection / omega for every sample.
                const double expectedPdf = selection.at(light) / solidAngle(tris[order[light]]);
                ASSERT_NEAR(a.y, expectedPdf, 2e-3 * expectedPdf) << "sample " << i;
            }
            const glm::dvec4 x(1.0 / a.y, glm::dvec3(glm::vec3(b)) / double(a.y));
            sums[order[light]].first += x;
            sums[order[light]].second += x * x;
        }
        for (uint32_t t = 0; t < 3; ++t) {
            const glm::dvec4 mean = sums[t].first / double(n);
            const glm::dvec4 var = sums[t].second / double(n) - mean * mean;
            const glm::dvec4 expected(solidAngle(tris[t]), directionIntegral(tris[t]));
            for (int k = 0; k < 4; ++k) {
                const double se = std::sqrt(std::max(var[k], 0.0) / double(n));
                EXPECT_NEAR(mean[k], expected[k], 5.0 * se + 1e-4 * std::abs(expected.x))
                    << "triangle " << t << " component " << k << (solid ? " solid" : " area");
            }
        }
    }
}

}  // namespace
