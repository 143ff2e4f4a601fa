// `fovea reference`: a converged image of a scene, the ground truth every error figure is
// measured against. It is `fovea run` on graphs/reference.json (PathTrace + Accumulate) with the
// frame count derived from the requested samples per pixel, a progress bar and an ETA.
#include <cmath>
#include <filesystem>

#include "apps/fovea/CliChecks.h"
#include "apps/fovea/Commands.h"
#include "apps/fovea/GraphRunner.h"
#include "apps/fovea/Progress.h"
#include "core/graph/Param.h"
#include "core/graph/PassRegistry.h"
#include "core/util/Error.h"
#include "eval/reference/ReferenceErrors.h"

namespace fovea::app {

namespace fs = std::filesystem;

void addReferenceCommand(CLI::App& app, ReferenceOptions& o) {
    auto* cmd = app.add_subcommand(
        "reference", "render a converged reference image (PathTrace + Accumulate) of a scene");
    o.run.graph.graph = (fs::path(FOVEA_SOURCE_DIR) / "graphs" / "reference.json").string();
    cmd->add_option("--graph", o.run.graph.graph,
                    "reference graph (default: graphs/reference.json of this source tree)");
    cmd->add_flag("--pixel-centres", o.pixelCentres,
                  "primary rays through pixel centres, no jitter (graphs/"
                  "reference_pixel_centres.json): the reference of a denoiser's own error when its "
                  "input path tracer starts at the GBuffer's pixel-centre hits");
    cmd->add_option("--path-frame", o.pathFrame,
                    "hold the camera at this frame of the --camera path (per-frame references "
                    "of a moving camera, one run each)")
        ->check(CLI::Range(int64_t(0), int64_t(1) << 40));
    cmd->add_option("--spp", o.spp, "samples per pixel in total (default 1024)")
        ->check(CLI::Range(1, 1 << 24));
    cmd->add_option("--size", o.run.graph.size, "render size WIDTHxHEIGHT (default: the graph's)")
        ->check(nonEmptyValue());
    cmd->add_option("--out", o.run.out, "output directory (default: out/reference/<scene>)")
        ->check(nonEmptyValue())
        ->check(userPath());
    cmd->add_option("--set", o.run.graph.sets, "override a parameter: pass.param=value");
    cmd->add_option("--seed", o.run.seed, "random seed (default 0)")->check(nonNegativeInt64());
    cmd->add_option("--device", o.run.device, "GPU index or name substring")
        ->check(nonEmptyValue());
    cmd->add_flag("--validation", o.run.validation, "enable the Vulkan validation layer");
    cmd->add_flag("--overwrite", o.run.overwrite, "allow writing into a non-empty directory");
    cmd->add_flag("--quiet", o.run.quiet, "no progress bar");
    addSceneOptions(*cmd, o.run.scene);
}

uint32_t referenceSamplesPerFrame(const graph::GraphDesc& desc, const std::string& graphFile) {
    uint32_t perFrame = 0;
    for (const auto& p : desc.passes) {
        if (!p.enabled) continue;
        // The pass reports its samples per frame from its parameters as loaded (Pass::facts).
        auto pass = graph::passRegistry().create(p.type, p.name);
        graph::loadParams(*pass, p.params, graphFile, p.pointer + "/params");
        const std::optional<uint32_t> spp = pass->facts().samplesPerFrame;
        if (!spp) continue;
        if (perFrame != 0 && *spp != perFrame)
            throw InputError(graphFile, "/passes",
                             "reference graphs need one samples-per-frame count; path tracing "
                             "passes disagree");
        perFrame = *spp;
    }
    if (perFrame == 0)
        throw InputError(graphFile, "/passes",
                         "a reference graph needs a path tracing pass (e.g. PathTrace)");
    return perFrame;
}

uint32_t referenceFrames(uint32_t spp, uint32_t samplesPerFrame) {
    return uint32_t((uint64_t(spp) + samplesPerFrame - 1) / samplesPerFrame);  // >= 1
}

image::ImageRGBA renderReferenceImage(gpu::Context& ctx, RunScene& scene,
                                      const graph::GraphDesc& desc, const std::string& graphFile,
                                      uint32_t spp, const GraphRunConfig& config,
                                      const std::string& output, const std::string& outputOption,
                                      bool quiet) {
    const uint32_t perFrame = referenceSamplesPerFrame(desc, graphFile);
    const uint32_t frames = referenceFrames(spp, perFrame);
    GraphRunner runner(ctx, scene, desc, config);
    const std::string compared = selectComparedOutput(runner, output, outputOption);
    Progress progress(frames, perFrame, quiet);
    for (uint32_t f = 0; f < frames; ++f) {
        runner.runFrame();
        progress.update(f + 1);
    }
    progress.finish();
    return runner.download(compared);
}

int referenceCommand(ReferenceOptions o) {
    const fs::path defaultGraph = fs::path(FOVEA_SOURCE_DIR) / "graphs" / "reference.json";
    if (o.pixelCentres) {
        if (o.run.graph.graph != defaultGraph.string())
            throw InputError("--pixel-centres", "", "chooses the graph itself; drop --graph");
        o.run.graph.graph =
            (fs::path(FOVEA_SOURCE_DIR) / "graphs" / "reference_pixel_centres.json").string();
    }
    if (o.pathFrame >= 0) {
        if (o.run.scene.camera.empty())
            throw InputError("--path-frame", "", "needs --camera (a camera path)");
        o.run.fixedCameraFrame = uint64_t(o.pathFrame);
    }
    // Samples per frame = the `spp` of the graph's PathTrace pass(es) after --set overrides.
    const uint32_t perFrame = referenceSamplesPerFrame(loadGraph(o.run.graph), o.run.graph.graph);
    const uint32_t frames = referenceFrames(uint32_t(o.spp), perFrame);
    o.run.frames = int(frames);
    o.run.saveFrames = "last";
    o.run.samplesPerFrame = perFrame;
    if (o.run.out.empty()) {
        std::string name = o.run.scene.scene.empty() ? std::string("default") : o.run.scene.scene;
        if (name.rfind("builtin:", 0) == 0) name = name.substr(8);
        o.run.out = (fs::path("out") / "reference" / fs::path(name).stem()).string();
    }
    return runCommand(o.run);
}

}  // namespace fovea::app
