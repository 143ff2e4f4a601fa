// Per-kernel GPU time of BMFR (P2 Table 4's split: accumulation, fit, weighted sum, second
// accumulation) on builtin:cornell, GBuffer -> PathTrace 1 spp -> BMFR, static camera. A
// benchmark, not a test: DISABLED_ so ctest never runs it. Run it with
//   build-a/tests/fovea_tests --gtest_also_run_disabled_tests --gtest_filter='BMFRBench.*'
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/scene/BuiltinScenes.h"
#include "core/scene/Camera.h"
#include "core/scene/SceneGpu.h"
#include "passes/BMFR/BMFRPass.h"
#include "passes/RegisterPasses.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::graph;

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? -1.0 : v[v.size() / 2];
}

class BMFRBench : public test::GpuTest {
protected:
    static void SetUpTestSuite() { registerBuiltinPasses(); }
};

}  // namespace

TEST_F(BMFRBench, DISABLED_KernelTimes) {
    scene::Scene s = scene::loadBuiltinScene("builtin:cornell");
    scene::SceneGpu gpuScene(ctx(), s);
    const scene::CameraDesc camera = s.cameras.empty() ? s.defaultCamera() : s.cameras.front();
    const std::string text = R"({ "version": 1, "name": "bmfr_bench", "passes": [
        { "name": "gb", "type": "GBuffer" },
        { "name": "pt", "type": "PathTrace", "params": { "spp": 1 } },
        { "name": "bmfr", "type": "BMFR", "params": { "timings": true } } ],
      "edges": [ { "from": "gb.visibility", "to": "pt.visibility" },
                 { "from": "gb.albedo", "to": "pt.albedo" },
                 { "from": "pt.demodulated", "to": "bmfr.color" },
                 { "from": "gb.position", "to": "bmfr.position" },
                 { "from": "gb.normal", "to": "bmfr.normal" },
                 { "from": "gb.albedo", "to": "bmfr.albedo" },
                 { "from": "gb.emission", "to": "bmfr.emission" } ],
      "outputs": [ "bmfr.filtered" ] })";
    for (uint32_t size : {128u, 256u}) {
        CompileOptions o;
        o.width = o.height = size;
        o.sceneFeatures = gpuScene.features();
        RenderGraph g(ctx(), passRegistry());
        g.setScene(&gpuScene);
        g.build(parseGraphText(text, "bmfr_bench"), o);
        passes::BMFRPass* pass = nullptr;
        size_t node = 0;
        for (size_t i = 0; i < g.plan().nodes.size(); ++i)
            if (g.plan().nodes[i].name == "bmfr") {
                pass = dynamic_cast<passes::BMFRPass*>(g.plan().nodes[i].pass.get());
                node = i;
            }
        ASSERT_NE(pass, nullptr);
        std::vector<double> kernels[4];
        constexpr int kFrames = 12, kWarmup = 2;
        for (int f = 0; f < kFrames + 1; ++f) {
            g.setCamera(
                scene::makeFrameCamera(camera, size, size, {}, g.frameIndex(), nullptr, nullptr));
            g.runFrame();
            // kernelMs() holds the previous frame's times (read at the start of execute).
            if (f > kWarmup)
                for (int k = 0; k < 4; ++k) kernels[k].push_back(pass->kernelMs()[size_t(k)]);
        }
        const auto& passMs = g.records()[node].gpuMs;
        std::vector<double> total(passMs.begin() + kWarmup, passMs.end());
        std::printf(
            "BMFR %ux%u (median of %zu frames, ms): accumulate %.3f  fit %.3f  weighted sum "
            "%.3f  second accumulation %.3f  | whole pass %.3f\n",
            size, size, kernels[0].size(), median(kernels[0]), median(kernels[1]),
            median(kernels[2]), median(kernels[3]), median(total));
    }
}
