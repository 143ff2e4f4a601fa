// CPU oracles of the specular ReBLUR formulas (shaders/recurrent_blur/reblur_specular.glsl; seed
// 004 "Cooking specular denoiser", issue 26): each written again in double precision from the
// talk's slides and compared with the shader on a grid of roughness, view angle, parallax, hit
// distance and normals; plus the limits the issue names: roughness 1 behaves like the diffuse
// path (full accumulation at any parallax, kernel in the tangent plane, isotropic) and roughness
// 0 gives no spatial blur and no accumulation through surface motion.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <numbers>
#include <vector>

#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;

namespace {

using dvec3 = glm::dvec3;
constexpr double kPi = std::numbers::pi;
constexpr double kMaxFrames = 30.0, kBasePower = 0.66, kCurve = 1.0, kK = 0.5;

double sat(double x) {
    return std::clamp(x, 0.0, 1.0);
}
dvec3 reflectD(const dvec3& i, const dvec3& n) {
    return i - 2.0 * glm::dot(n, i) * n;
}

// Slide "GGX dominant direction".
dvec3 dominantDirection(const dvec3& n, const dvec3& v, double r) {
    const double f = (1.0 - r) * (std::sqrt(1.0 - r) + r);
    return glm::normalize(n + (reflectD(-v, n) - n) * f);
}
// Slide "Sample weight - normal": 90 deg m / (1 + m).
double halfAngle(double r) {
    return kPi / 2.0 * r * r / (1.0 + r * r);
}
// Slide "Specular accumulation using surface motion".
double maxFrames(double r, double nov, double parallax) {
    const double a = std::pow(sat(1.0 - nov), kCurve);
    const double b = 1.001 + r * r;
    const double power = kBasePower * (1.0 + parallax * (b + a) / (b - a));
    return kMaxFrames * std::pow(r, power);
}
// Slide "Using hit distance to control blur radius".
double radiusFactor(double hitDist, double d, double r) {
    const double f = hitDist / (hitDist + d);
    return kK * r + (1.0 - kK * r) * f;
}
// Slide "Sample weight - roughness".
double roughnessWeight(double r0, double r) {
    return sat(1.0 - std::abs(r0 - r) / (r0 * r0 * 0.99 + 0.01));
}
// Slide "Sample weight - normal" with the optional 0.5 deg.
double normalWeight(const dvec3& n0, const dvec3& n, double r, double shrink) {
    const double a0 = halfAngle(r) * shrink + 0.5 * kPi / 180.0;
    return sat(1.0 - std::acos(std::clamp(glm::dot(n0, n), -1.0, 1.0)) / a0);
}
double radiusScale(double r) {
    return (1.0 - std::exp2(-200.0 * r * r)) * std::pow(r, 0.25);
}

struct Query {
    dvec3 n, v, n2;
    double roughness, nov, parallax, hitDist, viewDist, roughness2, shrink, frames, worldRadius;
};

class RecurrentBlurSpecularOracle : public GpuTest {
protected:
    // The shader's results, 4 vec4 per query (see shaders/test/reblur_specular.comp).
    static std::vector<glm::vec4> evaluate(const std::vector<Query>& qs) {
        std::vector<glm::vec4> in;
        for (const Query& q : qs) {
            in.emplace_back(glm::vec3(q.n), float(q.roughness));
            in.emplace_back(glm::vec3(q.v), float(q.parallax));
            in.emplace_back(float(q.nov), float(q.hitDist), float(q.viewDist), float(q.roughness2));
            in.emplace_back(glm::vec3(q.n2), float(q.shrink));
            in.emplace_back(float(q.frames), float(q.worldRadius), 0.0f, 0.0f);
        }
        const auto n = uint32_t(qs.size());
        const auto usage = vk::BufferUsageFlagBits::eStorageBuffer |
                           vk::BufferUsageFlagBits::eTransferSrc |
                           vk::BufferUsageFlagBits::eTransferDst;
        gpu::Buffer qb(ctx(), in.size() * 16, usage, false, "queries");
        gpu::Buffer rb(ctx(), size_t(n) * 4 * 16, usage, false, "results");
        qb.upload(ctx(), in.data(), in.size() * 16);
        gpu::ComputePipeline pipe(ctx(), "test/reblur_specular.comp");
        pipe.bind("test_queries", qb).bind("test_results", rb);
        pipe.set("count", n)
            .set("maxFrames", float(kMaxFrames))
            .set("basePower", float(kBasePower))
            .set("curve", float(kCurve))
            .set("k", float(kK));
        ctx().submitAndWait([&](const vk::raii::CommandBuffer& cmd) { pipe.dispatch(cmd, n); });
        return rb.downloadAs<glm::vec4>(ctx());
    }
};

// A view direction at angle theta from n (in the n-x plane).
dvec3 viewAt(const dvec3& n, const dvec3& x, double theta) {
    return glm::normalize(n * std::cos(theta) + x * std::sin(theta));
}

TEST_F(RecurrentBlurSpecularOracle, ShaderMatchesTheSlidesOnAGrid) {
    std::vector<Query> qs;
    const dvec3 n = glm::normalize(dvec3(0.2, 0.9, -0.3));
    const dvec3 x = glm::normalize(glm::cross(n, dvec3(0, 0, 1)));
    for (double r : {0.0, 0.05, 0.2, 0.4, 0.7, 1.0})
        for (double theta : {0.0, 0.4, 0.9, 1.3, 1.55})
            for (double parallax : {0.0, 0.3, 2.0}) {
                Query q;
                q.n = n;
                q.v = viewAt(n, x, theta);
                q.nov = std::cos(theta);
                q.roughness = r;
                q.parallax = parallax;
                q.hitDist = 0.1 + 3.0 * parallax;
                q.viewDist = 2.0;
                q.roughness2 = std::clamp(r + 0.03 * (parallax - 1.0), 0.0, 1.0);
                q.n2 = viewAt(n, glm::cross(n, x), 0.02 + 0.1 * parallax);
                q.shrink = 0.25 + 0.375 * parallax;
                q.frames = theta / 1.55;
                q.worldRadius = 0.5;
                qs.push_back(q);
            }
    const auto out = evaluate(qs);
    for (size_t i = 0; i < qs.size(); ++i) {
        const Query& q = qs[i];
        const std::string at = "roughness " + std::to_string(q.roughness) + " NoV " +
                               std::to_string(q.nov) + " parallax " + std::to_string(q.parallax);
        const dvec3 d = dominantDirection(q.n, q.v, q.roughness);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[4 * i][c], d[c], 1e-5) << at;
        EXPECT_NEAR(out[4 * i].w, halfAngle(q.roughness), 1e-6) << at;
        const double mf = maxFrames(q.roughness, q.nov, q.parallax);
        EXPECT_NEAR(out[4 * i + 1].x, mf, 1e-4 * (1.0 + mf)) << at;
        EXPECT_NEAR(out[4 * i + 1].y, radiusFactor(q.hitDist, q.viewDist, q.roughness), 1e-6) << at;
        EXPECT_NEAR(out[4 * i + 1].z, roughnessWeight(q.roughness, q.roughness2), 1e-5) << at;
        // acos near 1 loses digits in float: an absolute 2e-3 on a weight in [0, 1].
        EXPECT_NEAR(out[4 * i + 1].w, normalWeight(q.n, q.n2, q.roughness, q.shrink), 2e-3) << at;
        EXPECT_NEAR(out[4 * i + 2].w, radiusScale(q.roughness), 1e-5) << at;
        // Kernel basis (slides "Unifying ..." and "Anisotropic sampling"): T _|_ n and R, B _|_ R
        // and T, |B| = worldRadius, |T| = worldRadius x lerp(1, lerp(1, r, angle), frames).
        const glm::dvec3 t(out[4 * i + 2]), b(out[4 * i + 3]);
        const dvec3 rr = reflectD(-d, q.n);
        const double angle = std::acos(sat(std::abs(q.nov))) / (kPi / 2.0);
        const double skew = 1.0 + (q.roughness - 1.0) * angle;
        const double tLength = q.worldRadius * (1.0 + (skew - 1.0) * q.frames);
        EXPECT_NEAR(glm::length(t), tLength, 2e-4) << at;  // float acos: ~1e-4 rad
        EXPECT_NEAR(glm::length(b), q.worldRadius, 1e-5) << at;
        EXPECT_NEAR(glm::dot(t, q.n), 0.0, 1e-5) << at;
        EXPECT_NEAR(glm::dot(t, rr), 0.0, 1e-5) << at;
        EXPECT_NEAR(glm::dot(b, rr), 0.0, 1e-5) << at;
    }
}

TEST_F(RecurrentBlurSpecularOracle, RoughnessOneIsTheDiffuseKernelAndRoughnessZeroDoesNotBlur) {
    const dvec3 n(0, 1, 0);
    std::vector<Query> qs;
    for (double r : {1.0, 0.0})
        for (double theta : {0.1, 0.8, 1.4})
            for (double parallax : {0.0, 1.0, 10.0}) {
                Query q{};
                q.n = n;
                q.v = viewAt(n, dvec3(1, 0, 0), theta);
                q.nov = std::cos(theta);
                q.roughness = r;
                q.parallax = parallax;
                q.hitDist = 1.0;
                q.viewDist = 1.0;
                q.roughness2 = r;
                q.n2 = n;
                q.shrink = 1.0;
                q.frames = 1.0;
                q.worldRadius = 1.0;
                qs.push_back(q);
            }
    const auto out = evaluate(qs);
    for (size_t i = 0; i < qs.size(); ++i) {
        const Query& q = qs[i];
        if (q.roughness == 1.0) {
            // Accumulation as the diffuse path at any parallax and angle; the dominant
            // direction is the normal, the kernel lies in the tangent plane and is isotropic.
            EXPECT_NEAR(out[4 * i + 1].x, kMaxFrames, 1e-4);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(out[4 * i][c], n[c], 1e-6);
            const glm::dvec3 t(out[4 * i + 2]), b(out[4 * i + 3]);
            EXPECT_NEAR(glm::dot(t, n), 0.0, 1e-5);
            EXPECT_NEAR(glm::dot(b, n), 0.0, 1e-5);
            EXPECT_NEAR(glm::length(t), glm::length(b), 1e-5);
            EXPECT_NEAR(out[4 * i + 2].w, 1.0, 1e-6) << "full radius";
        } else {
            // A mirror: no accumulation through surface motion, no radius, and the kernel plane
            // is the screen plane (perpendicular to the view vector).
            EXPECT_EQ(out[4 * i + 1].x, 0.0f);
            EXPECT_EQ(out[4 * i + 2].w, 0.0f) << "radius scale";
            const glm::dvec3 t(out[4 * i + 2]), b(out[4 * i + 3]);
            EXPECT_NEAR(glm::dot(t, q.v), 0.0, 1e-5);
            EXPECT_NEAR(glm::dot(b, q.v), 0.0, 1e-5);
        }
    }
    // Parallax shortens the accumulation of a glossy lobe, more at grazing angles.
    EXPECT_GT(maxFrames(0.4, 0.9, 0.0), maxFrames(0.4, 0.9, 1.0));
    EXPECT_GT(maxFrames(0.4, 0.9, 1.0), maxFrames(0.4, 0.2, 1.0));
}

}  // namespace
