// GPU tests of glTF alpha coverage (glTF 2.0 §3.9.4; docs/scenes.md "Alpha") in GBuffer and
// PathTrace: the any-hit test inside the compute BVH traversal (shaders/common/bvh.glsl).
//
// The scene: a diffuse floor (y = 0, albedo 0.5) lit by a directional light shining straight
// down (E = 2 lux), under a 4 x 4 card at y = 1 that covers the light for the whole view of a
// camera between them looking down (direct light only: the floor's radiance is rho / pi * E where
// the shadow ray is open, 0 where the card stops it, with no noise). A camera above the card
// sees the card everywhere unless its rays pass through. Checked:
// - MASK with cutoff 0 draws exactly as opaque, and compiling the any-hit test in (another
//   material of the scene is BLEND) leaves an opaque scene's images bit for bit unchanged;
// - an all-transparent card (alpha 0 from the factor, or from COLOR_0) casts no shadow and is
//   invisible to GBuffer's and PathTrace's own primary rays; an opaque one does both;
// - a checker of alpha 0 / 1 lets through half the light, each pixel all or nothing;
// - BLEND with alpha a transmits 1 - a of the light in expectation over frames, noisy per
//   frame, the same on a rerun; primary rays see it in a fraction a of the pixels;
// - a MASK checker that emits: shadow rays only and BRDF rays only agree (next-event estimation
//   weights the emission by coverage).
// Each of the last four fails with the any-hit test disabled (checked by hand).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
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

constexpr float kFloorAlbedo = 0.5f;
constexpr float kSunLux = 2.0f;
// The floor's radiance where the light reaches it: Lambert, rho / pi * E * cos 0.
const double kLitFloor = kFloorAlbedo / std::numbers::pi * kSunLux;
constexpr uint32_t kAlphaSize = 32;

struct Card {
    scene::AlphaMode mode = scene::AlphaMode::Opaque;
    float cutoff = 0.5f;
    float alpha = 1.0f;        // baseColorFactor.a
    bool checker = false;      // baseColorTexture: 64 x 64 checker of alpha 0 / 1
    float vertexAlpha = 1.0f;  // COLOR_0.a of the card's vertices (no COLOR_0 when 1)
    // A small triangle far below the floor, where no ray goes, with an alpha-tested material:
    // SCENE_HAS_ALPHA = 1 for a scene whose visible materials are all opaque.
    bool hiddenBlend = false;
    bool hiddenOpaque = false;  // the same triangle, opaque (same BVH, SCENE_HAS_ALPHA = 0)
    float emission = 0.0f;      // > 0: the card is a double-sided emitter and the sun is off
};

scene::Scene cardScene(const std::string& name, const Card& card) {
    scene::Scene s;
    s.source = name;
    auto material = [&](float albedo, float alpha) {
        scene::Material m;
        m.name = "m" + std::to_string(s.materials.size());
        m.baseColor = glm::vec4(glm::vec3(albedo), alpha);
        m.metallic = 0.0f;
        s.materials.push_back(m);
        return uint32_t(s.materials.size() - 1);
    };
    const uint32_t floor = material(kFloorAlbedo, 1.0f);
    const uint32_t cardMaterial = material(0.8f, card.alpha);
    scene::Material& cm = s.materials[cardMaterial];
    cm.alphaMode = card.mode;
    cm.alphaCutoff = card.cutoff;
    cm.emissive = glm::vec3(card.emission);
    cm.doubleSided = card.emission > 0.0f;
    if (card.checker) {
        scene::Texture t;
        t.name = "checker";
        t.width = t.height = 64;
        t.rgba8.assign(size_t(64) * 64 * 4, 200);
        for (uint32_t y = 0; y < 64; ++y)
            for (uint32_t x = 0; x < 64; ++x)
                t.rgba8[(size_t(y) * 64 + x) * 4 + 3] = (x + y) % 2 ? 255 : 0;
        s.textures.push_back(std::move(t));
        cm.baseColorTexture = 0;
    }
    scene::MeshBuilder b(s.mesh);
    const glm::vec3 up(0, 1, 0);
    b.quadFacing({-3, 0, -3}, {3, 0, -3}, {3, 0, 3}, {-3, 0, 3}, floor, up);
    const uint32_t firstCardVertex = uint32_t(s.mesh.positions.size());
    const uint32_t c0 = b.vertex({-2, 1, -2}, up, {0, 0}), c1 = b.vertex({2, 1, -2}, up, {1, 0}),
                   c2 = b.vertex({2, 1, 2}, up, {1, 1}), c3 = b.vertex({-2, 1, 2}, up, {0, 1});
    b.indexed(c0, c2, c1, cardMaterial);  // counter-clockwise seen from +y
    b.indexed(c0, c3, c2, cardMaterial);
    if (card.hiddenBlend || card.hiddenOpaque) {
        const uint32_t hidden = material(0.5f, 0.5f);
        if (card.hiddenBlend) s.materials[hidden].alphaMode = scene::AlphaMode::Blend;
        b.triangleFacing({0, -10, 0}, {0.1f, -10, 0}, {0, -10, 0.1f}, hidden, {0, -11, 0});
    }
    if (card.vertexAlpha != 1.0f) {
        s.mesh.colors.assign(s.mesh.positions.size(), glm::vec4(1.0f));
        for (uint32_t v = firstCardVertex; v < firstCardVertex + 4; ++v)
            s.mesh.colors[v].a = card.vertexAlpha;
    }
    scene::Light sun;
    sun.type = scene::Light::Type::Directional;
    sun.name = "sun";
    sun.direction = {0, -1, 0};
    sun.intensity = kSunLux;
    if (card.emission == 0.0f) s.lights.push_back(sun);
    for (const glm::vec3& p : s.mesh.positions) s.bounds.grow(p);
    // cameras[0]: between card and floor, looking down (sees the floor lit through the card).
    scene::CameraDesc below;
    below.position = {0.0f, 0.5f, 0.0f};
    below.target = {0.0f, 0.0f, 0.0f};
    below.up = {0.0f, 0.0f, -1.0f};
    below.yfov = 1.2f;
    below.znear = 1e-3f;
    // cameras[1]: above the card, which fills its view.
    scene::CameraDesc above = below;
    above.position = {0.0f, 3.0f, 0.0f};
    above.yfov = 0.8f;
    s.cameras = {below, above};
    return s;
}

struct Frame {
    std::vector<float> radiance;  // pt.radiance
    std::vector<float> material;  // gb.material (material id + 1; empty without GBuffer)
};

class AlphaMaskTest : public GpuTest {
protected:
    static void SetUpTestSuite() { registerBuiltinPasses(); }

    static test::LoadedScene& scene(const std::string& name, const Card& card) {
        return test::loadedScene(name, [&](const std::string& n) { return cardScene(n, card); });
    }

    // `frames` frames of GBuffer + PathTrace (or PathTrace's own camera rays without GBuffer),
    // seen from cameras[camera].
    static std::vector<Frame> render(test::LoadedScene& s, int camera, bool gbuffer, int frames,
                                     int spp = 1, int bounces = 0, uint64_t seed = 1,
                                     const std::string& extraParams = "") {
        const std::string pt = R"({ "name": "pt", "type": "PathTrace", "params": { "spp": )" +
                               std::to_string(spp) + R"(, "maxBounces": )" +
                               std::to_string(bounces) + extraParams + " } }";
        const std::string text =
            gbuffer ? R"({ "version": 1, "name": "alpha", "passes": [ { "name": "gb", "type": )"
                      R"("GBuffer" }, )" +
                          pt +
                          R"( ], "edges": [ { "from": "gb.visibility", "to": "pt.visibility" } )"
                          R"(], "outputs": [ "pt.radiance", "gb.material" ] })"
                    : R"({ "version": 1, "name": "alpha", "passes": [ )" + pt +
                          R"( ], "outputs": [ "pt.radiance" ] })";
        auto g = test::buildSceneGraph(s, text, "alpha", seed, kAlphaSize, kAlphaSize);
        std::vector<Frame> out;
        for (int f = 0; f < frames; ++f) {
            g->setCamera(scene::makeFrameCamera(s.scene.cameras.at(size_t(camera)), kAlphaSize,
                                                kAlphaSize, {}, g->frameIndex(), nullptr, nullptr));
            g->runFrame();
            Frame frame;
            frame.radiance = g->image("pt.radiance").downloadRGBA32F(ctx());
            if (gbuffer) frame.material = g->image("gb.material").downloadRGBA32F(ctx());
            out.push_back(std::move(frame));
        }
        return out;
    }
};

constexpr int kBelow = 0, kAbove = 1;
constexpr float kCardId = 2.0f;  // gb.material = material index + 1; the card is material 1

// Mean of the red channel over the pixels (all channels are equal: grey materials).
double meanRed(const std::vector<float>& rgba) {
    double sum = 0;
    for (size_t i = 0; i < rgba.size(); i += 4) sum += rgba[i];
    return sum / double(rgba.size() / 4);
}

double cardFraction(const std::vector<float>& material) {
    size_t card = 0;
    for (size_t i = 0; i < material.size(); i += 4) card += material[i] == kCardId;
    return double(card) / double(material.size() / 4);
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

TEST_F(AlphaMaskTest, CutoffZeroRendersExactlyAsOpaque) {
    Card opaque;
    Card zero;  // every texel has alpha 0, and still none is below a cutoff of 0
    zero.mode = scene::AlphaMode::Mask;
    zero.cutoff = 0.0f;
    zero.checker = true;
    zero.alpha = 0.0f;
    Card opaqueTextured = zero;
    opaqueTextured.mode = scene::AlphaMode::Opaque;
    test::LoadedScene& a = scene("alpha:opaque-textured", opaqueTextured);
    test::LoadedScene& b = scene("alpha:cutoff-0", zero);
    EXPECT_FALSE(b.gpu->features() & kSceneAlpha) << "no any-hit test to compile in";
    for (int camera : {kBelow, kAbove}) {
        Frame fa = render(a, camera, true, 1, 2, 1).front();
        Frame fb = render(b, camera, true, 1, 2, 1).front();
        EXPECT_TRUE(sameBits(fa.radiance, fb.radiance)) << "camera " << camera;
        EXPECT_TRUE(sameBits(fa.material, fb.material)) << "camera " << camera;
    }

    // The any-hit test compiled in (a BLEND triangle no ray reaches) changes nothing for the
    // opaque card: same BVH, SCENE_HAS_ALPHA 1 against 0.
    Card withBlend = opaque, withOpaque = opaque;
    withBlend.hiddenBlend = true;
    withOpaque.hiddenOpaque = true;
    test::LoadedScene& on = scene("alpha:hidden-blend", withBlend);
    test::LoadedScene& off = scene("alpha:hidden-opaque", withOpaque);
    ASSERT_TRUE(on.gpu->features() & kSceneAlpha);
    ASSERT_FALSE(off.gpu->features() & kSceneAlpha);
    for (int camera : {kBelow, kAbove}) {
        for (bool gbuffer : {true, false}) {
            Frame fOn = render(on, camera, gbuffer, 1, 2, 1).front();
            Frame fOff = render(off, camera, gbuffer, 1, 2, 1).front();
            EXPECT_TRUE(sameBits(fOn.radiance, fOff.radiance))
                << "camera " << camera << " gbuffer " << gbuffer;
            EXPECT_TRUE(sameBits(fOn.material, fOff.material)) << "camera " << camera;
            // From above the lit card fills the view (below it, its shadow is black).
            if (camera == kAbove) {
                EXPECT_GT(meanRed(fOn.radiance), 0.1);
            }
        }
    }
}

// Transparent through the factor's alpha or COLOR_0's: no shadow (the floor is lit as without a
// card) and invisible from above (GBuffer and PathTrace's own rays both see the floor). The
// opaque card (alpha 1 >= cutoff) is the control: full shadow, seen everywhere.
TEST_F(AlphaMaskTest, TransparentCardCastsNoShadowAndIsInvisible) {
    Card clearFactor, clearVertex, solid;
    clearFactor.mode = clearVertex.mode = solid.mode = scene::AlphaMode::Mask;
    clearFactor.alpha = 0.0f;
    clearVertex.vertexAlpha = 0.2f;  // < 0.5: cut, whatever the factor (1)
    struct Case {
        const char* name;
        Card card;
        bool transparent;
    };
    for (const Case& c :
         {Case{"alpha:clear-factor", clearFactor, true},
          Case{"alpha:clear-vertex", clearVertex, true}, Case{"alpha:mask-solid", solid, false}}) {
        test::LoadedScene& s = scene(c.name, c.card);
        ASSERT_TRUE(s.gpu->features() & kSceneAlpha) << c.name;
        Frame lit = render(s, kBelow, true, 1).front();
        const double floorLight = meanRed(lit.radiance);
        if (c.transparent) {
            EXPECT_NEAR(floorLight, kLitFloor, 1e-4 * kLitFloor) << c.name;
        } else {
            EXPECT_EQ(floorLight, 0.0) << c.name;
        }
        Frame top = render(s, kAbove, true, 1).front();
        EXPECT_EQ(cardFraction(top.material), c.transparent ? 0.0 : 1.0) << c.name;
        // PathTrace's own (jittered) camera rays: the floor's radiance, or the lit card's.
        const double seen = meanRed(render(s, kAbove, false, 1).front().radiance);
        const double expected = c.transparent ? kLitFloor : 0.8 / std::numbers::pi * kSunLux;
        EXPECT_NEAR(seen, expected, 1e-4 * expected) << c.name;
    }
}

// A checker of alpha 0 / 1 texels (bilinear alpha crosses 0.5 on the texel borders): half the
// card is open, so the floor under it gets half the light, every pixel all or nothing. The view
// spans ~5.5 x 5.5 of 64 texels per 4 units, so the open fraction of the window is 0.5 within
// 0.5 * (texel / window)^2 = 0.002 (the checker's imbalance is at most one texel per axis).
TEST_F(AlphaMaskTest, CheckerCardLetsThroughTheOpenFraction) {
    Card checker;
    checker.mode = scene::AlphaMode::Mask;
    checker.checker = true;
    test::LoadedScene& s = scene("alpha:checker", checker);
    const std::vector<float> floor = render(s, kBelow, true, 1).front().radiance;
    size_t partial = 0;
    for (size_t i = 0; i < floor.size(); i += 4)
        partial += floor[i] > 1e-4 * kLitFloor && floor[i] < (1.0 - 1e-4) * kLitFloor;
    EXPECT_EQ(partial, 0u) << "MASK is all or nothing per shadow ray";
    const double open = meanRed(floor) / kLitFloor;
    std::printf("[ alpha ] checker: %.4f of the light passes\n", open);
    EXPECT_NEAR(open, 0.5, 0.03);
    // From above, primary rays see the card through the same holes.
    const double seen = cardFraction(render(s, kAbove, true, 1).front().material);
    EXPECT_NEAR(seen, 0.5, 0.08);
}

// BLEND with alpha 0.3: each ray passes with probability 0.7, so the shadow transmits 0.7 of the
// light in expectation. 32 x 32 pixels x 4 spp x 4 frames = 16384 Bernoulli samples: standard
// error sqrt(0.21 / 16384) = 0.0036, checked at 6 of them. One frame is noisy (pixels differ),
// a rerun with the same seed is bit-identical, another seed is not.
TEST_F(AlphaMaskTest, BlendShadowTransmitsOneMinusAlpha) {
    Card blend;
    blend.mode = scene::AlphaMode::Blend;
    blend.alpha = 0.3f;
    test::LoadedScene& s = scene("alpha:blend", blend);
    const std::vector<Frame> frames = render(s, kBelow, true, 4, 4);
    double sum = 0;
    for (const Frame& f : frames) sum += meanRed(f.radiance);
    const double transmitted = sum / double(frames.size()) / kLitFloor;
    std::printf("[ alpha ] blend 0.3: %.4f of the light passes\n", transmitted);
    EXPECT_NEAR(transmitted, 0.7, 6 * 0.0036);
    double lo = 1e30, hi = -1e30;
    for (size_t i = 0; i < frames[0].radiance.size(); i += 4) {
        lo = std::min(lo, double(frames[0].radiance[i]));
        hi = std::max(hi, double(frames[0].radiance[i]));
    }
    EXPECT_LT(lo, 0.5 * kLitFloor) << "stochastic: some pixels are mostly shadowed";
    EXPECT_GT(hi, 0.9 * kLitFloor) << "stochastic: some pixels are fully lit";
    EXPECT_TRUE(sameBits(render(s, kBelow, true, 1, 4).front().radiance, frames[0].radiance));
    EXPECT_FALSE(
        sameBits(render(s, kBelow, true, 1, 4, 0, 2).front().radiance, frames[0].radiance));

    // Primary rays: GBuffer sees the card in a fraction 0.3 of the pixels (1024 Bernoulli
    // samples: standard error 0.014), a new pattern each frame.
    const std::vector<Frame> top = render(s, kAbove, true, 2);
    for (const Frame& f : top) EXPECT_NEAR(cardFraction(f.material), 0.3, 0.07);
    EXPECT_FALSE(sameBits(top[0].material, top[1].material));
}

// A MASK checker card that emits (both sides) over the floor, no other light: next-event
// estimation samples points on the whole card, BRDF rays pass through its holes. The two
// single-strategy estimators (emitterSampling light / brdf) must agree: next-event estimation
// weights the sampled point's emission by its coverage (0 in a hole). Without that weight the
// shadow-ray estimate would count the holes' emission too, twice the BRDF estimate. Compared per
// pixel (the difference of two independent estimates of the same value), 32 x 32 x 16 spp x 2.
TEST_F(AlphaMaskTest, MaskedEmitterStrategiesAgree) {
    Card light;
    light.mode = scene::AlphaMode::Mask;
    light.checker = true;
    light.emission = 3.0f;
    test::LoadedScene& s = scene("alpha:masked-emitter", light);
    ASSERT_TRUE(s.gpu->features() & kSceneEmissive);
    auto mean = [&](const char* strategy, uint64_t seed) {
        const std::string params = std::string(R"(, "emitterSampling": ")") + strategy + "\"";
        std::vector<double> image;
        for (const Frame& f : render(s, kBelow, true, 2, 16, 0, seed, params)) {
            image.resize(f.radiance.size() / 4, 0.0);
            for (size_t i = 0; i < image.size(); ++i) image[i] += 0.5 * f.radiance[4 * i];
        }
        return image;
    };
    const std::vector<double> shadowRays = mean("light", 3), brdfRays = mean("brdf", 4);
    double sum = 0, sum2 = 0, level = 0;
    const double n = double(shadowRays.size());
    for (size_t i = 0; i < shadowRays.size(); ++i) {
        const double d = shadowRays[i] - brdfRays[i];
        sum += d;
        sum2 += d * d;
        level += brdfRays[i] / n;
    }
    const double meanDiff = sum / n;
    const double stderrDiff = std::sqrt(std::max(0.0, sum2 / n - meanDiff * meanDiff) / n);
    std::printf("[ alpha ] masked emitter: light - brdf = %.5f +- %.5f (level %.4f)\n", meanDiff,
                stderrDiff, level);
    ASSERT_GT(level, 0.05);
    EXPECT_LT(std::abs(meanDiff), 5.0 * stderrDiff + 1e-3 * level);
    EXPECT_LT(std::abs(meanDiff), 0.1 * level) << "a missing coverage weight doubles one side";
}

}  // namespace
