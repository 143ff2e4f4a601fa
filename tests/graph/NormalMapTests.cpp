// GPU tests of normal textures (glTF 2.0 §3.9.3; sceneApplyNormalMap in scene_sample.glsl): a
// Lambertian plane whose normal texture tilts the shading normal, lit by a directional light
// from straight above, reflects exactly rho / pi * E * cos(tilt) (one delta light, no noise), and
// GBuffer's `normal` (the denoisers' guide) is the tilted normal; normalTexture.scale scales the
// tilt (0: the flat normal); without tangents the texture is not applied. With PathTrace's
// bumpShadowing a sun from the side the normal leans towards is darkened by exactly Chiang et
// al.'s term (2019, the one Cycles applies), computed here on the CPU.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "core/graph/RenderGraph.h"
#include "core/scene/BuiltinGeometry.h"
#include "core/scene/Camera.h"
#include "core/scene/SceneGpu.h"
#include "core/vk/Resources.h"
#include "passes/RegisterPasses.h"
#include "tests/graph/SceneGraphRig.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::graph;

namespace {

constexpr float kAlbedoRho = 0.5f, kSun = 3.0f;
// The tangent-space normal stored in the texture: 30 degrees towards +T (8-bit, as written).
const glm::u8vec3 kTexel(191, 128, 238);

scene::Scene tiltedPlane(float normalScale, bool withTangents,
                         glm::vec3 sunTravels = {0.0f, -1.0f, 0.0f}) {
    scene::Scene s;
    s.source = "test:normal-map";
    scene::Material m;
    m.baseColor = glm::vec4(glm::vec3(kAlbedoRho), 1.0f);
    m.metallic = 0.0f;
    m.normalTexture = 0;
    m.normalScale = normalScale;
    s.materials.push_back(m);
    scene::Texture t;
    t.width = t.height = 1;
    t.rgba8 = {kTexel.x, kTexel.y, kTexel.z, 255};
    s.textures.push_back(t);
    scene::MeshBuilder b(s.mesh);
    const float k = 10.0f;
    b.quadFacing({-k, 0, -k}, {k, 0, -k}, {k, 0, k}, {-k, 0, k}, 0, {0, 1, 0});
    if (withTangents) s.mesh.tangents.assign(s.mesh.positions.size(), glm::vec4(1, 0, 0, 1));
    scene::Light sun;
    sun.type = scene::Light::Type::Directional;
    sun.direction = sunTravels;
    sun.intensity = kSun;
    s.lights.push_back(sun);
    for (const glm::vec3& p : s.mesh.positions) s.bounds.grow(p);
    return s;
}

// The shading normal the texel and scale give on the +Y plane with T = +X, B = cross(N, T) = -Z.
glm::vec3 expectedNormal(float scale) {
    glm::vec3 n = glm::vec3(kTexel) / 255.0f * 2.0f - 1.0f;
    n.x *= scale;
    n.y *= scale;
    return glm::normalize(glm::vec3(n.x, n.z, -n.y));
}

// Chiang, Li & Burley 2019: g = (Ng.wi) / ((Ns.wi)(Ng.Ns)); G = 1 above 1, else -g^3 + g^2 + g.
double bumpShadowingTerm(glm::dvec3 ng, glm::dvec3 ns, glm::dvec3 wi) {
    const double g = glm::dot(ng, wi) / (glm::dot(ns, wi) * glm::dot(ng, ns));
    return g >= 1.0 ? 1.0 : g <= 0.0 ? 0.0 : -g * g * g + g * g + g;
}

// GBuffer + PathTrace (direct light only, `ptParams` added to its params) on `loaded`, 8x8
// looking straight down at the plane; one frame run.
std::unique_ptr<graph::RenderGraph> renderFromAbove(const test::LoadedScene& loaded,
                                                    const std::string& ptParams,
                                                    const std::string& outputs) {
    const std::string text =
        R"({ "version": 1, "name": "nm", "passes": [ { "name": "gb", "type": "GBuffer" },)"
        R"( { "name": "pt", "type": "PathTrace", "params": { "maxBounces": 0)" +
        ptParams +
        R"( } } ], "edges": [ { "from": "gb.visibility", "to": "pt.visibility" } ],)"
        R"( "outputs": [ )" +
        outputs + " ] }";
    auto g = test::buildSceneGraph(loaded, text, "nm", 1, 8, 8);
    scene::CameraDesc c;
    c.position = {0.3f, 2.0f, 0.2f};
    c.target = {0.3f, 0.0f, 0.2f};
    c.up = {0.0f, 0.0f, -1.0f};
    g->setCamera(scene::makeFrameCamera(c, 8, 8, {}, 0, nullptr, nullptr));
    g->runFrame();
    return g;
}

class NormalMapTest : public GpuTest {
protected:
    static void SetUpTestSuite() { registerBuiltinPasses(); }
};

TEST_F(NormalMapTest, TiltedNormalShadesAndGuidesExactly) {
    for (float scale : {1.0f, 0.0f, 2.0f}) {
        for (bool withTangents : {true, false}) {
            test::LoadedScene loaded;
            loaded.scene = tiltedPlane(scale, withTangents);
            loaded.gpu = std::make_unique<scene::SceneGpu>(test::sharedGpuContext(), loaded.scene);
            EXPECT_EQ(loaded.gpu->hasNormalMaps(), withTangents);
            auto g = renderFromAbove(loaded, "", R"("pt.radiance", "gb.normal")");
            const auto radiance = g->image("pt.radiance").downloadRGBA32F(ctx());
            const auto normal = g->image("gb.normal").downloadRGBA32F(ctx());
            const glm::vec3 n = withTangents ? expectedNormal(scale) : glm::vec3(0, 1, 0);
            const float expected = kAlbedoRho / std::numbers::pi_v<float> * kSun * n.y;
            for (size_t i = 0; i < 64; ++i) {
                EXPECT_NEAR(radiance[4 * i], expected, 1e-5f)
                    << "scale " << scale << " tangents " << withTangents << " pixel " << i;
                for (int k = 0; k < 3; ++k)
                    EXPECT_NEAR(normal[4 * i + k], n[k], 2e-3f) << "scale " << scale << " " << k;
            }
        }
    }
}

TEST_F(NormalMapTest, BumpShadowingDarkensGrazingLightExactly) {
    // The sun comes from +X, 45 degrees up; the texel leans the normal 30 degrees towards it, so
    // g = cos 45 / (cos 15 cos 30) = 0.845 and the term is 0.956 (plain shading: cos 15).
    const glm::vec3 towardsSun = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));
    for (bool bumpShadowing : {false, true}) {
        for (bool withTangents : {true, false}) {
            test::LoadedScene loaded;
            loaded.scene = tiltedPlane(1.0f, withTangents, -towardsSun);
            loaded.gpu = std::make_unique<scene::SceneGpu>(test::sharedGpuContext(), loaded.scene);
            auto g = renderFromAbove(
                loaded, std::string(", \"bumpShadowing\": ") + (bumpShadowing ? "true" : "false"),
                R"("pt.radiance")");
            const auto radiance = g->image("pt.radiance").downloadRGBA32F(ctx());
            const glm::dvec3 n =
                withTangents ? glm::dvec3(expectedNormal(1.0f)) : glm::dvec3(0, 1, 0);
            const glm::dvec3 wi(towardsSun);
            double expected = kAlbedoRho / std::numbers::pi * kSun * glm::dot(n, wi);
            if (bumpShadowing) expected *= bumpShadowingTerm({0, 1, 0}, n, wi);
            if (bumpShadowing && withTangents) {
                EXPECT_LT(bumpShadowingTerm({0, 1, 0}, n, wi), 0.97);  // the case bites
            }
            for (size_t i = 0; i < 64; ++i)
                EXPECT_NEAR(radiance[4 * i], expected, 1e-5)
                    << "bumpShadowing " << bumpShadowing << " tangents " << withTangents
                    << " pixel " << i;
        }
    }
}

}  // namespace
