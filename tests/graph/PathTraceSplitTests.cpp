// PathTrace's diffuse / specular split (issue 26; seed 004 "Cooking specular denoiser": the two
// signals are separated and demodulated before denoising; docs/passes/PathTrace.md "Diffuse and
// specular signals"): remodulating both and adding the primary emission gives `radiance` back
// pixel by pixel, Lambert has no specular signal, the hit distances are normalized, and a metal's
// light is all specular.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/scene/BuiltinScenes.h"
#include "core/scene/Camera.h"
#include "core/vk/Resources.h"
#include "passes/RegisterPasses.h"
#include "tests/graph/SceneGraphRig.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;

namespace {

constexpr uint32_t kSplitSize = 48;

class PathTraceSplitTest : public GpuTest {
protected:
    static void SetUpTestSuite() { registerBuiltinPasses(); }

    static test::LoadedScene& cornell() {
        return test::loadedScene("builtin:cornell",
                                 [](const std::string& n) { return scene::loadBuiltinScene(n); });
    }

    // GBuffer-fed PathTrace (every sample shades the pixel's one primary point, so the split
    // inverts exactly) with `params`, one frame.
    static std::unique_ptr<graph::RenderGraph> render(const std::string& params) {
        const std::string text =
            R"({ "version": 1, "name": "split", "passes": [ { "name": "gb", "type": "GBuffer" },)"
            R"( { "name": "pt", "type": "PathTrace", "params": )" +
            params +
            R"( } ], "edges": [ { "from": "gb.visibility", "to": "pt.visibility" } ],)"
            R"( "outputs": [ "pt.radiance", "pt.diffuse", "pt.specular", "pt.diffuse_albedo",)"
            R"( "pt.specular_albedo", "pt.demodulated", "pt.diffuse_hit", "pt.specular_hit",)"
            R"( "gb.emission" ] })";
        auto g = test::buildSceneGraph(cornell(), text, "split", 7, kSplitSize, kSplitSize);
        g->setCamera(scene::makeFrameCamera(cornell().camera, kSplitSize, kSplitSize, {}, 0,
                                            nullptr, nullptr));
        g->runFrame();
        return g;
    }

    static std::vector<float> px(const graph::RenderGraph& g, const std::string& r) {
        return g.image(r).downloadRGBA32F(ctx());
    }
};

float safe(float albedo) {
    return albedo > 1e-3f ? albedo : 1.0f;
}

TEST_F(PathTraceSplitTest, RemodulatedSignalsAddUpToRadiance) {
    for (const std::string brdf : {"lambert", "ggx"}) {
        auto g = render(R"({ "spp": 2, "maxBounces": 3, "brdf": ")" + brdf + "\" }");
        const auto rad = px(*g, "pt.radiance"), dif = px(*g, "pt.diffuse"),
                   spe = px(*g, "pt.specular"), da = px(*g, "pt.diffuse_albedo"),
                   sa = px(*g, "pt.specular_albedo"), em = px(*g, "gb.emission");
        size_t bad = 0;
        double specularSum = 0.0;
        for (size_t i = 0; i < rad.size(); i += 4)
            for (int c = 0; c < 3; ++c) {
                const float back =
                    dif[i + c] * safe(da[i + c]) + spe[i + c] * safe(sa[i + c]) + em[i + c];
                bad += !(std::fabs(back - rad[i + c]) <= 2e-3f * (1.0f + rad[i + c]));
                specularSum += spe[i + c] * safe(sa[i + c]);
            }
        EXPECT_EQ(bad, 0u) << brdf << ": remodulated diffuse + specular + emission != radiance";
        if (brdf == "ggx")
            EXPECT_GT(specularSum, 0.0) << "F0 = 0.04 reflects some light specularly";
        else
            EXPECT_EQ(specularSum, 0.0) << "Lambert has no specular lobe";
    }
}

TEST_F(PathTraceSplitTest, LambertDiffuseIsTheDemodulatedSignalAndHitDistancesAreNormalized) {
    auto g = render(R"({ "spp": 1, "maxBounces": 1 })");
    const auto dif = px(*g, "pt.diffuse"), dem = px(*g, "pt.demodulated"),
               spe = px(*g, "pt.specular"), sa = px(*g, "pt.specular_albedo"),
               dh = px(*g, "pt.diffuse_hit"), sh = px(*g, "pt.specular_hit");
    size_t differ = 0, near = 0, noData = 0;
    for (size_t i = 0; i < dif.size(); i += 4) {
        for (int c = 0; c < 4; ++c) {  // alpha too: samples
            differ += !(std::fabs(dif[i + c] - dem[i + c]) <= 1e-5f * (1.0f + dem[i + c]));
            if (c == 3) continue;  // samples
            EXPECT_EQ(spe[i + c], 0.0f);
            EXPECT_EQ(sa[i + c], 0.0f);
        }
        EXPECT_EQ(sh[i], -1.0f) << "no specular ray: no data";
        if (dh[i] == -1.0f) {  // sky (no primary hit): no ray
            ++noData;
            continue;
        }
        EXPECT_GE(dh[i], 0.0f);
        EXPECT_LE(dh[i], 1.0f);
        near += dh[i] < 1.0f;
    }
    EXPECT_EQ(differ, 0u) << "with Lambert the diffuse signal is PathTrace.demodulated";
    EXPECT_LT(noData, dif.size() / 4 / 10) << "Lambert: every surface pixel traces a diffuse ray";
    // Inside the box most bounce rays hit a wall closer than the view's frustum size.
    EXPECT_GT(near, dif.size() / 4 / 2);
}

}  // namespace
