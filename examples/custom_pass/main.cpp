// fovea as a library: register an own pass next to the built-in ones, build a graph from C++,
// run one frame headless and check the output read back. Exit 0 when every pixel is right.
#include <cmath>
#include <cstdlib>
#include <iostream>

#include "InvertPass.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/vk/Context.h"
#include "passes/RegisterPasses.h"

using namespace fovea;

int main() {
    // fovea's own shaders (common/ for #include) from the package unless the user says otherwise.
    setenv("FOVEA_SHADER_DIR", FOVEA_INSTALLED_SHADER_DIR, 0);
    registerBuiltinPasses();
    graph::passRegistry().add({"Invert", "white - color (examples/custom_pass)",
                               [] { return std::make_unique<InvertPass>(EXAMPLE_SHADER_DIR); }});

    graph::GraphDesc desc;
    desc.name = "custom pass example";
    desc.passes = {{"src", "ImageSource", {{"pattern", "constant"}, {"value", {0.25, 0.5, 0.75}}}},
                   {"inv", "Invert", {{"white", 2.0}}}};
    desc.edges = {{{"src", "color"}, {"inv", "color"}}};
    desc.outputs = {{{"inv", "result"}}};

    try {
        gpu::Context ctx;  // FOVEA_VALIDATION=1 turns the validation layer on
        graph::RenderGraph graph(ctx, graph::passRegistry());
        graph::CompileOptions options;
        options.width = 16;
        options.height = 8;
        graph.build(desc, options);
        graph.runFrame();
        const std::vector<float> px = graph.image("inv.result").downloadRGBA32F(ctx);
        const float expected[3] = {1.75f, 1.5f, 1.25f};
        int bad = 0;
        for (size_t i = 0; i < px.size(); i += 4)
            for (int c = 0; c < 3; ++c)
                if (std::fabs(px[i + c] - expected[c]) > 1e-6f) ++bad;
        if (ctx.validationMessageCount() > 0) {
            std::cerr << "custom_pass: " << ctx.validationMessageCount()
                      << " validation message(s)\n";
            return 1;
        }
        if (bad > 0 || px.size() != 16 * 8 * 4) {
            std::cerr << "custom_pass: " << bad << " wrong values of " << px.size() << "\n";
            return 1;
        }
        std::cout << "custom_pass: ok (" << px.size() / 4 << " pixels of 2 - (0.25, 0.5, 0.75))\n";
    } catch (const std::exception& e) {
        std::cerr << "custom_pass: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
