// GPU tests of the environment light (docs/scenes.md "Environment light"; shaders/common/
// environment.glsl) in GBuffer and PathTrace, against analytic values:
// - the white furnace: a convex, flat-shaded sphere of albedo rho under a constant environment L
//   reflects exactly rho L (every ray leaving it escapes), and the background reads L;
// - a sky over a ground plane: radiance rho / pi * sum_k L_k * (integral of cos over texel k),
//   exact for the piecewise-constant map, with a bright "sun" block that only importance sampling
//   finds quickly; the same with a directional light added (--sun's kind of light);
// - the two single strategies (shadow rays only, BRDF rays only) and MIS agree with each other
//   and with that value, also when an emissive quad shares next-event estimation with the sky (a
//   wrong selection probability on either side moves MIS's mean);
// - the background GBuffer writes (emission) and PathTrace decodes (visibility.yz) is the
//   texel the CPU mapping gives, with a rotation.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "core/graph/RenderGraph.h"
#include "core/scene/BuiltinGeometry.h"
#include "core/scene/Camera.h"
#include "core/scene/Environment.h"
#include "core/scene/SceneGpu.h"
#include "core/vk/Resources.h"
#include "passes/RegisterPasses.h"
#include "tests/graph/SceneGraphRig.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::graph;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr float kRho = 0.5f;

uint32_t diffuse(scene::Scene& s, float albedo, const glm::vec3& emission = glm::vec3(0.0f)) {
    scene::Material m;
    m.name = "m" + std::to_string(s.materials.size());
    m.baseColor = glm::vec4(glm::vec3(albedo), 1.0f);
    m.emissive = emission;
    m.metallic = 0.0f;
    s.materials.push_back(m);
    return uint32_t(s.materials.size() - 1);
}

void finish(scene::Scene& s) {
    for (const glm::vec3& p : s.mesh.positions) s.bounds.grow(p);
}

// A sky: a blue gradient above the horizon, dark ground below, and a 2x1-texel "sun" of radiance
// 150 high in the sky (14 % of the sky's irradiance on a plane: found by light samples only).
scene::EnvironmentMap skyMap(float rotationDegrees = 0.0f, bool sun = true) {
    const uint32_t w = 32, h = 16;
    scene::EnvironmentMap map = scene::constantEnvironment(glm::vec3(0.0f), w, h);
    map.rotation = float(rotationDegrees * kPi / 180.0);
    for (uint32_t j = 0; j < h; ++j)
        for (uint32_t i = 0; i < w; ++i) {
            const float v = (j + 0.5f) / h;
            glm::vec3 c =
                v < 0.5f ? glm::vec3(0.3f, 0.5f, 1.0f) * (1.2f - v) : glm::vec3(0.1f, 0.08f, 0.05f);
            if (sun && i >= 8 && i < 10 && j == 3) c = glm::vec3(150.0f, 140.0f, 120.0f);
            map.radiance[size_t(j) * w + i] = c;
        }
    return map;
}

// rho / pi * sum over the texels above the horizon of L_k * integral of cos(theta) dw over the
// texel = (2 pi / W) (sin^2 theta_bottom - sin^2 theta_top) / 2. H is even: no row straddles it.
glm::dvec3 skyOnGround(const scene::EnvironmentMap& map) {
    glm::dvec3 e(0.0);
    for (uint32_t j = 0; j < map.height / 2; ++j) {
        const double a = kPi * j / map.height, b = kPi * (j + 1.0) / map.height;
        const double cosIntegral =
            2.0 * kPi / map.width * 0.5 * (std::pow(std::sin(b), 2) - std::pow(std::sin(a), 2));
        for (uint32_t i = 0; i < map.width; ++i)
            e += glm::dvec3(map.radiance[size_t(j) * map.width + i]) * cosIntegral;
    }
    return double(kRho) / kPi * e;
}

// A flat-shaded UV sphere of radius 1 (convex: no ray leaving a facet meets another one).
scene::Scene furnaceSphere() {
    scene::Scene s;
    s.source = "test:env-sphere";
    const uint32_t m = diffuse(s, kRho);
    scene::MeshBuilder b(s.mesh);
    const int rings = 12, segments = 24;
    auto point = [&](int r, int g) {
        const double theta = kPi * r / rings, phi = 2.0 * kPi * g / segments;
        return glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                         float(std::sin(theta) * std::sin(phi)));
    };
    for (int r = 0; r < rings; ++r)
        for (int g = 0; g < segments; ++g) {
            const glm::vec3 a = point(r, g), bb = point(r, g + 1), c = point(r + 1, g + 1),
                            d = point(r + 1, g);
            const glm::vec3 out = 0.25f * (a + bb + c + d) * 2.0f;  // outside the facet
            if (r > 0) b.triangleFacing(a, bb, c, m, out);
            if (r < rings - 1) b.triangleFacing(a, c, d, m, out);
        }
    finish(s);
    scene::CameraDesc c;
    c.position = {0.0f, 0.0f, 4.0f};
    c.target = {0.0f, 0.0f, 0.0f};
    c.yfov = 0.7f;
    s.cameras.push_back(c);
    s.environment =
        std::make_shared<scene::EnvironmentMap>(scene::constantEnvironment(glm::vec3(1.0f)));
    return s;
}

// A ground plane (y = 0, +-1000) seen from 1 above; `sun`: a directional light as --sun adds;
// `emitter`: a small one-sided emissive quad above the plane, facing down.
scene::Scene skyPlane(const std::string& name, bool sun, bool emitter, bool sunTexels) {
    scene::Scene s;
    s.source = name;
    const uint32_t ground = diffuse(s, kRho);
    scene::MeshBuilder b(s.mesh);
    const float k = 1000.0f;
    b.quadFacing({-k, 0, -k}, {k, 0, -k}, {k, 0, k}, {-k, 0, k}, ground, {0, 1, 0});
    if (emitter) {
        const uint32_t light = diffuse(s, 0.0f, glm::vec3(4.0f));
        b.quadFacing({-0.3f, 1.5f, -0.3f}, {0.3f, 1.5f, -0.3f}, {0.3f, 1.5f, 0.3f},
                     {-0.3f, 1.5f, 0.3f}, light, {0, -1, 0});
    }
    if (sun) {
        scene::Light l;
        l.type = scene::Light::Type::Directional;
        l.name = "sun";
        l.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
        l.intensity = 3.0f;
        s.lights.push_back(l);
    }
    finish(s);
    scene::CameraDesc c;
    c.position = {0.0f, 1.0f, 0.0f};
    c.target = {0.0f, 0.0f, 0.0f};
    c.up = {0.0f, 0.0f, -1.0f};
    c.yfov = 1.0f;
    s.cameras.push_back(c);
    s.environment = std::make_shared<scene::EnvironmentMap>(skyMap(0.0f, sunTexels));
    return s;
}

scene::Scene namedScene(const std::string& name) {
    if (name == "test:env-sphere") return furnaceSphere();
    if (name == "test:env-plane") return skyPlane(name, false, false, true);
    if (name == "test:env-plane-sun") return skyPlane(name, true, false, true);
    if (name == "test:env-plane-emitter") return skyPlane(name, false, true, false);
    ADD_FAILURE() << "no scene " << name;
    return {};
}

struct Mean {
    double value = 0, stderr_ = 0;
    size_t pixels = 0;
};

class EnvironmentLightTest : public GpuTest {
protected:
    static void SetUpTestSuite() { registerBuiltinPasses(); }

    static test::LoadedScene& sceneNamed(const std::string& name) {
        return test::loadedScene(name, namedScene);
    }

    // GBuffer (optional) + PathTrace; `frames` frames of `spp` samples; per-pixel means of the
    // channel `channel` of pt.radiance over the frames, and the mean over the pixels `use` keeps
    // with its standard error from the per-pixel sample variances.
    static std::vector<std::vector<float>> run(const std::string& sceneName,
                                               const std::string& strategy, bool gbuffer,
                                               int frames, uint32_t size = 32, int spp = 4,
                                               uint64_t seed = 1) {
        const std::string pt = R"({ "name": "pt", "type": "PathTrace", "params": { "spp": )" +
                               std::to_string(spp) + R"(, "maxBounces": 1, "emitterSampling": ")" +
                               strategy + R"(" } })";
        const std::string text =
            gbuffer ? R"({ "version": 1, "name": "env", "passes": [ { "name": "gb", "type": )"
                      R"("GBuffer" }, )" +
                          pt +
                          R"( ], "edges": [ { "from": "gb.visibility", "to": "pt.visibility" } )"
                          R"(], "outputs": [ "pt.radiance", "gb.emission" ] })"
                    : R"({ "version": 1, "name": "env", "passes": [ )" + pt +
                          R"( ], "outputs": [ "pt.radiance" ] })";
        test::LoadedScene& s = sceneNamed(sceneName);
        auto g = test::buildSceneGraph(s, text, "env", seed, size, size);
        std::vector<std::vector<float>> out;
        for (int f = 0; f < frames; ++f) {
            g->setCamera(scene::makeFrameCamera(s.camera, size, size, {}, g->frameIndex(), nullptr,
                                                nullptr));
            g->runFrame();
            out.push_back(g->image("pt.radiance").downloadRGBA32F(ctx()));
            if (gbuffer && f == 0) mEmission = g->image("gb.emission").downloadRGBA32F(ctx());
        }
        return out;
    }

    static Mean meanOf(const std::vector<std::vector<float>>& frames, int channel,
                       const std::vector<bool>& use) {
        const size_t n = frames[0].size() / 4;
        double sum = 0, var = 0;
        Mean m;
        for (size_t i = 0; i < n; ++i) {
            if (!use[i]) continue;
            double s = 0, s2 = 0;
            for (const auto& f : frames) {
                s += f[4 * i + channel];
                s2 += double(f[4 * i + channel]) * f[4 * i + channel];
            }
            const double k = double(frames.size()), mean = s / k;
            sum += mean;
            var += std::max(0.0, (s2 - k * mean * mean) / (k - 1)) / k;
            ++m.pixels;
        }
        if (m.pixels == 0) return m;
        m.value = sum / double(m.pixels);
        m.stderr_ = std::sqrt(var) / double(m.pixels);
        return m;
    }

    static std::vector<float> mEmission;
};
std::vector<float> EnvironmentLightTest::mEmission;

std::vector<bool> all(size_t n) {
    return std::vector<bool>(n, true);
}

// The white furnace: sphere pixels rho L, background pixels exactly L, with each strategy; the
// sphere is found by the GBuffer's rays and by PathTrace's own (jittered) camera rays.
TEST_F(EnvironmentLightTest, FurnaceSphereReflectsAlbedoTimesL) {
    for (const char* strategy : {"mis", "light", "brdf"}) {
        const auto frames = run("test:env-sphere", strategy, true, 4);
        const size_t n = frames[0].size() / 4;
        std::vector<bool> sphere(n), background(n);
        // A pixel is background where every sample of the first frame returned exactly L.
        for (size_t i = 0; i < n; ++i) {
            background[i] = frames[0][4 * i] == 1.0f && frames[0][4 * i + 1] == 1.0f;
            sphere[i] = !background[i];
        }
        const Mean s = meanOf(frames, 1, sphere), b = meanOf(frames, 1, background);
        std::printf("[ ENV ] furnace %-5s sphere %.5f +- %.5f (%zu px), background %.5f (%zu)\n",
                    strategy, s.value, s.stderr_, s.pixels, b.value, b.pixels);
        ASSERT_GT(s.pixels, 200u);
        ASSERT_GT(b.pixels, 200u);
        EXPECT_NEAR(s.value, kRho, 5.0 * s.stderr_ + 2e-3) << strategy;
        EXPECT_EQ(b.value, 1.0) << strategy;  // the GBuffer's direction decodes to a texel of 1
        for (size_t i = 0; i < n; ++i) {
            if (background[i]) {
                EXPECT_EQ(mEmission[4 * i + 1], 1.0f) << "GBuffer emission " << i;
            }
        }
    }
    // Own camera rays (no GBuffer): the same sphere value, background L where a pixel's samples
    // all miss (pixels on the silhouette mix both).
    const auto own = run("test:env-sphere", "mis", false, 4);
    const Mean m = meanOf(own, 1, all(own[0].size() / 4));
    const auto withGbuffer = run("test:env-sphere", "mis", true, 4, 32, 4, 2);
    const Mean g = meanOf(withGbuffer, 1, all(own[0].size() / 4));
    EXPECT_NEAR(m.value, g.value, 5.0 * std::hypot(m.stderr_, g.stderr_) + 0.02);
}

// The sky over a plane, per channel, with each strategy, against the exact integral.
TEST_F(EnvironmentLightTest, SkyOnAPlaneMatchesTheIntegral) {
    const glm::dvec3 expected = skyOnGround(skyMap());
    for (const char* strategy : {"mis", "light", "brdf"}) {
        // BRDF rays alone find the 2-texel sun rarely: more frames for a usable error bar.
        const int frames = std::string(strategy) == "brdf" ? 16 : 4;
        const auto f = run("test:env-plane", strategy, true, frames);
        for (int c = 0; c < 3; ++c) {
            const Mean m = meanOf(f, c, all(f[0].size() / 4));
            std::printf("[ ENV ] sky %-5s channel %d: %.5f +- %.5f, expected %.5f\n", strategy, c,
                        m.value, m.stderr_, expected[c]);
            EXPECT_NEAR(m.value, expected[c], 5.0 * m.stderr_ + 1e-3 * expected[c])
                << strategy << " channel " << c;
        }
    }
}

// The sky plus a directional light: E cos / pi * rho more, whatever the split of next-event
// samples between the two (the environment's selection probability scales both pdfs).
TEST_F(EnvironmentLightTest, SkyAndSunAddUp) {
    const glm::vec3 toSun = -glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
    const double sun = double(kRho) / kPi * 3.0 * toSun.y;
    const glm::dvec3 expected = skyOnGround(skyMap()) + glm::dvec3(sun);
    const auto f = run("test:env-plane-sun", "mis", true, 4);
    for (int c = 0; c < 3; ++c) {
        const Mean m = meanOf(f, c, all(f[0].size() / 4));
        EXPECT_NEAR(m.value, expected[c], 5.0 * m.stderr_ + 1e-3 * expected[c]) << c;
    }
}

// An emissive quad and the sky share next-event estimation: light-only, BRDF-only and MIS give
// the same image mean (MIS weights use both pdfs with their selection probabilities).
TEST_F(EnvironmentLightTest, StrategiesAgreeWithAnEmitterAndTheSky) {
    std::vector<Mean> means;
    for (const char* strategy : {"light", "brdf", "mis"}) {
        const auto f = run("test:env-plane-emitter", strategy, true, 8);
        means.push_back(meanOf(f, 1, all(f[0].size() / 4)));
        std::printf("[ ENV ] emitter+sky %-5s %.5f +- %.5f\n", strategy, means.back().value,
                    means.back().stderr_);
    }
    for (int i = 0; i < 2; ++i)
        EXPECT_NEAR(means[2].value, means[i].value,
                    5.0 * std::hypot(means[2].stderr_, means[i].stderr_))
            << "strategy " << i;
    // The quad adds light: more than the sky alone.
    EXPECT_GT(means[2].value, skyOnGround(skyMap(0.0f, false)).g * 1.05);
}

// Looking along +X and with a rotation: the background GBuffer writes and PathTrace shows is the
// texel the CPU mapping (environmentRadiance) picks for the centre pixel's ray.
TEST_F(EnvironmentLightTest, BackgroundFollowsTheMappingAndRotation) {
    for (float rotation : {0.0f, 100.0f}) {
        scene::Scene s;
        s.source = "test:env-background";
        const uint32_t m = diffuse(s, kRho);
        scene::MeshBuilder b(s.mesh);  // a small triangle behind the camera: geometry, not seen
        b.triangleFacing({0, -5, 5}, {0.1f, -5, 5}, {0, -4.9f, 5}, m, {0, 0, 1});
        finish(s);
        s.environment = std::make_shared<scene::EnvironmentMap>(skyMap(rotation));
        test::LoadedScene loaded;
        loaded.scene = s;
        loaded.gpu = std::make_unique<scene::SceneGpu>(test::sharedGpuContext(), loaded.scene);
        ASSERT_TRUE(loaded.gpu->features() & scene::kSceneEnvironment);
        const std::string text =
            R"({ "version": 1, "name": "bg", "passes": [ { "name": "gb", "type": "GBuffer" },)"
            R"( { "name": "pt", "type": "PathTrace" } ], "edges": [ { "from": "gb.visibility",)"
            R"( "to": "pt.visibility" } ], "outputs": [ "pt.radiance", "gb.emission" ] })";
        auto g = test::buildSceneGraph(loaded, text, "bg", 1, 9, 9);
        scene::CameraDesc c;
        c.position = {0, 0, 0};
        for (const glm::vec3 target : {glm::vec3(1, 0.3f, 0), glm::vec3(-0.2f, 0.5f, 1)}) {
            c.target = target;
            g->setCamera(scene::makeFrameCamera(c, 9, 9, {}, g->frameIndex(), nullptr, nullptr));
            g->runFrame();
            const auto radiance = g->image("pt.radiance").downloadRGBA32F(ctx());
            const auto emission = g->image("gb.emission").downloadRGBA32F(ctx());
            // The centre pixel's ray (pixel centre 4.5 of 9) is the camera's view direction.
            const glm::vec3 expected =
                scene::environmentRadiance(*s.environment, glm::normalize(target));
            const size_t centre = 4 * (4 * 9 + 4);
            for (int ch = 0; ch < 3; ++ch) {
                EXPECT_FLOAT_EQ(radiance[centre + ch], expected[ch]) << rotation << " " << ch;
                EXPECT_NEAR(emission[centre + ch], expected[ch], 1e-3 * expected[ch] + 1e-3);
            }
        }
    }
}

}  // namespace
