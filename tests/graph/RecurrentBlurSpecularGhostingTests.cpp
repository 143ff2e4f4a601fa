// Specular ReBLUR on the glossy floor of builtin:glossy while the camera trucks sideways
// (graphs/cameras/glossy_truck.json): the reflections move differently from the surfaces, so
// accumulating the specular signal through the surface motion alone ghosts (seed 004 "Specular
// accumulation using surface motion": "naive accumulation using surface motion doesn't work").
// The graph is graphs/reblur_diffuse_specular.json itself. Its error in the reflection region
// (the floor) against a converged per-frame reference stays below the same graph's with the
// parallax cap off (specAccumBasePower 0), and NaN/Inf never persist in the specular chain.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "core/scene/BuiltinScenes.h"
#include "core/scene/Camera.h"
#include "core/scene/CameraPath.h"
#include "core/vk/Resources.h"
#include "passes/RegisterPasses.h"
#include "tests/graph/GpuTestFixture.h"
#include "tests/graph/SceneGraphRig.h"

using namespace fovea;
namespace fs = std::filesystem;

namespace {

constexpr uint32_t kWidth = 96, kHeight = 54;
constexpr int kFrames = 12;

const fs::path kGraphs = fs::path(FOVEA_TEST_DIR) / ".." / "graphs";

class RecurrentBlurSpecularGhosting : public GpuTest {
protected:
    static void SetUpTestSuite() { registerBuiltinPasses(); }

    static test::LoadedScene& glossy() {
        return test::loadedScene("builtin:glossy",
                                 [](const std::string& n) { return scene::loadBuiltinScene(n); });
    }

    static nlohmann::json graphFile() {
        std::ifstream in(kGraphs / "reblur_diffuse_specular.json");
        nlohmann::json j = nlohmann::json::parse(in);
        j.erase("defaults");  // the test sets scene, size and camera itself
        j["outputs"] = {"rbss.result", "gb.roughness_metallic", "gb.depth"};
        return j;
    }

    // Runs `text` along the truck path for `frames` frames; returns the graph.
    static std::unique_ptr<graph::RenderGraph> runPath(const std::string& text, int frames) {
        const auto path = scene::CameraPath::load(kGraphs / "cameras" / "glossy_truck.json");
        auto g = test::buildSceneGraph(glossy(), text, "ghosting", 3, kWidth, kHeight);
        scene::FrameCamera previous;
        for (int f = 0; f < frames; ++f) {
            const scene::FrameCamera cam =
                scene::makeFrameCamera(path.at(uint64_t(f)).camera, kWidth, kHeight, {},
                                       uint64_t(f), f > 0 ? &previous : nullptr, nullptr);
            g->setCamera(cam);
            g->runFrame();
            previous = cam;
        }
        return g;
    }

    static std::vector<float> px(const graph::RenderGraph& g, const std::string& r) {
        return g.image(r).downloadRGBA32F(ctx());
    }
};

TEST_F(RecurrentBlurSpecularGhosting, ParallaxCapBeatsSurfaceMotionAccumulationOnTheFloor) {
    // Converged specular signal of the last frame (GBuffer-fed: the same primary points).
    const std::string reference =
        R"({ "version": 1, "name": "ref", "passes": [ { "name": "gb", "type": "GBuffer" },)"
        R"( { "name": "pt", "type": "PathTrace", "params": { "spp": 256, "brdf": "ggx" } } ],)"
        R"( "edges": [ { "from": "gb.visibility", "to": "pt.visibility" } ],)"
        R"( "outputs": [ "pt.specular" ] })";
    const std::vector<float> ref = px(*runPath(reference, kFrames), "pt.specular");

    auto rmseOnFloor = [&](float basePower, bool virtualMotion, bool& finite) {
        nlohmann::json j = graphFile();
        for (auto& p : j["passes"])
            if (p["name"] == "rbst") {
                p["params"]["specAccumBasePower"] = basePower;
                p["params"]["virtualMotion"] = virtualMotion;
            }
        auto g = runPath(j.dump(), kFrames);
        const auto out = px(*g, "rbss.result"), rough = px(*g, "gb.roughness_metallic"),
                   depth = px(*g, "gb.depth");
        double sum = 0.0;
        size_t n = 0;
        finite = true;
        for (size_t i = 0; i < out.size(); i += 4) {
            for (int c = 0; c < 4; ++c) finite = finite && std::isfinite(out[i + c]);
            // The floor: roughness 0.1 (the spheres' ramp skips it), a surface.
            if (!(depth[i] > 0.0f) || std::fabs(rough[i] - 0.1f) > 0.005f) continue;
            for (int c = 0; c < 3; ++c) {
                const double d = double(out[i + c]) - double(ref[i + c]);
                sum += d * d;
            }
            n += 3;
        }
        EXPECT_GT(n, size_t(kWidth * kHeight / 4)) << "the floor covers the lower image";
        return std::sqrt(sum / double(std::max<size_t>(n, 1)));
    };
    bool finiteDefault = false, finiteNaive = false, finiteCapOnly = false;
    const double byDefault = rmseOnFloor(0.66f, true, finiteDefault);
    const double naive = rmseOnFloor(0.0f, false, finiteNaive);
    const double capOnly = rmseOnFloor(0.66f, false, finiteCapOnly);
    std::printf(
        "[ ReBLUR specular ] floor RMSE after %d truck frames: default (parallax cap + "
        "virtual motion) %.4f, surface motion only %.4f, parallax cap only %.4f\n",
        kFrames, byDefault, naive, capOnly);
    EXPECT_TRUE(finiteDefault && finiteNaive && finiteCapOnly);
    EXPECT_LT(byDefault, naive);
}

}  // namespace
