// Graph JSON, as `fovea validate` reads it: the text parser (GraphDescParse), every pass's
// parameter loading and validate(), and the CPU compile stages (culling, order, resources,
// aliasing, barriers) with a scene that has every feature and one that has none. Also checks the
// canonical form's promise (GraphDesc.h): parseGraphJson(graphToJson(g)) == g.
#include <string_view>

#include "core/graph/CompilerStages.h"
#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/scene/SceneFeatures.h"
#include "passes/RegisterPasses.h"
#include "tests/fuzz/FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace fovea;
    registerBuiltinPasses();
    fuzz::expectOnlyInputErrors("graph", [&] {
        const std::string_view text(reinterpret_cast<const char*>(data), size);
        const graph::GraphDesc desc = graph::parseGraphText(text, "fuzz.json");
        if (!(graph::parseGraphJson(graph::graphToJson(desc), "fuzz.json") == desc)) {
            std::fprintf(stderr, "fuzz graph: graphToJson does not round-trip\n");
            std::abort();
        }
        // No scene, and a scene with everything seen through the graph's camera model (the
        // foveation passes refuse an equirect camera, PreviewSamples a pinhole).
        const uint32_t everything = desc.defaults.cameraModel.value_or("perspective") == "equirect"
                                        ? ~0u
                                        : ~uint32_t(scene::kSceneEquirect);
        for (uint32_t features : {0u, everything}) {
            graph::CompileOptions options;
            options.width = 64;
            options.height = 48;
            options.sceneFeatures = features;
            const graph::CompiledPlan plan =
                graph::compileGraphPlan(desc, graph::passRegistry(), options);
            (void)graph::dumpPlanJson(plan).dump();
        }
    });
    return 0;
}
