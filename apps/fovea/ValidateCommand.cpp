// `fovea validate`: run every CPU compile stage (no device needed) and optionally dump the plan.
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>

#include "apps/fovea/CliChecks.h"
#include "apps/fovea/Commands.h"
#include "core/graph/CompilerStages.h"

namespace fovea::app {

void addValidateCommand(CLI::App& app, ValidateOptions& o) {
    auto* cmd = app.add_subcommand("validate", "check a graph file without running it");
    cmd->add_option("graph", o.graph.graph, "graph file (JSON)")->required()->check(userPath());
    cmd->add_option("--size", o.graph.size, "render size WIDTHxHEIGHT for size checks")
        ->check(nonEmptyValue());
    cmd->add_option("--set", o.graph.sets, "override a parameter: pass.param=value (repeatable)");
    cmd->add_flag("--no-aliasing", o.graph.noAliasing, "plan without memory aliasing");
    cmd->add_flag("--dump", o.dump,
                  "print the compiled graph (order, culling, resources, "
                  "aliasing, barriers, memory)");
    cmd->add_flag("--json", o.json, "with --dump: print it as JSON");
    addSceneOptions(*cmd, o.scene);
}

int validateCommand(const ValidateOptions& o) {
    graph::GraphDesc desc = loadGraph(o.graph);
    auto [width, height] = renderSize(o.graph, desc);
    graph::CompileOptions options;
    options.width = width;
    options.height = height;
    options.aliasing = !o.graph.noAliasing;
    // The scene is loaded on the CPU only: its features decide which passes are culled.
    RunScene scene(o.scene, desc);
    scene.checkRenderSize(width, height);
    // The same scene warnings `run` prints (no light, ignored glTF features, dropped camera).
    if (scene.hasScene()) {
        const nlohmann::json sceneJson = scene.json();  // a range-for over a temporary's member
        for (const auto& w : sceneJson.at("warnings"))  // would dangle
            std::cerr << "fovea: warning: " << w.get<std::string>() << "\n";
    }
    options.sceneFeatures = scene.features();
    auto t0 = std::chrono::steady_clock::now();
    graph::CompiledPlan plan = graph::compileGraphPlan(desc, graph::passRegistry(), options);
    const double compileMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (o.dump && o.json)
        std::cout << graph::dumpPlanJson(plan).dump(2) << "\n";
    else if (o.dump)
        std::cout << graph::dumpPlanText(plan);
    else
        std::cout << o.graph.graph << ": ok (" << plan.order.size() << " passes run, "
                  << plan.nodes.size() - plan.order.size() << " culled; plan compiled in "
                  << compileMs << " ms)\n";
    return kExitOk;
}

}  // namespace fovea::app
