// `fovea reference`: a converged image of a scene, the ground truth every error figure is
// measured against. It is `fovea run` on graphs/reference.json (PathTrace + Accumulate) with the
// frame count derived from the requested samples per pixel, a progress bar and an ETA.
#include <cmath>
#include <filesystem>

#include "apps/fovea/CliChecks.h"
#include "apps/fovea/Commands.h"
#include "core/graph/Param.h"
#include "core/graph/PassRegistry.h"
#include "core/util/Error.h"
#include "core/util/InstallPaths.h"
#include "core/vk/Context.h"
#include "eval/reference/ReferenceErrors.h"
#include "eval/reference/ReferenceRender.h"
#include "eval/reference/ReferenceShards.h"
#include "eval/report/OutputFolder.h"
#include "eval/run/GraphRunner.h"
#include "eval/run/Progress.h"

namespace fovea::app {

namespace fs = std::filesystem;

void addReferenceCommand(CLI::App& app, ReferenceOptions& o) {
    auto* cmd = app.add_subcommand(
        "reference", "render a converged reference image (PathTrace + Accumulate) of a scene");
    o.run.graph.graph = shippedGraph("reference.json");
    cmd->add_option("--graph", o.run.graph.graph,
                    "reference graph (default: graphs/reference.json of the install or source tree)");
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
    // Sharded references (docs/cluster.md): `fovea merge` combines the shards' folders.
    cmd->add_option("--shard", o.shard,
                    "render shard I of N (0-based) of the samples: its frames of the single "
                    "run, written as sum.exr + shard.json")
        ->check(nonEmptyValue());
    cmd->add_option("--path-frames", o.pathFrames,
                    "render the converged reference of every --camera path frame FIRST:LAST "
                    "(frameNNNN.exr each, + shard.json)")
        ->check(nonEmptyValue());
    cmd->add_option("--frames-of", o.framesOf,
                    "with --path-frames: render only shard I of N (0-based) of those frames")
        ->check(nonEmptyValue());
    addSceneOptions(*cmd, o.run.scene);
}

void addMergeCommand(CLI::App& app, MergeOptions& o) {
    auto* cmd = app.add_subcommand(
        "merge",
        "combine reference shards (fovea reference --shard / --frames-of) into the "
        "files of one reference (docs/cluster.md)");
    cmd->add_option("shards", o.shards, "the shards' output folders")
        ->required()
        ->check(CLI::ExistingDirectory);
    cmd->add_option("--out", o.out, "output directory of the merged reference")
        ->required()
        ->check(nonEmptyValue())
        ->check(userPath());
    cmd->add_flag("--overwrite", o.overwrite, "allow writing into a non-empty directory");
    cmd->add_flag("--quiet", o.quiet, "no summary on stderr");
}

int mergeCommand(const MergeOptions& o) {
    checkOutputDir(o.out, "--out", o.overwrite);
    std::vector<fs::path> shards(o.shards.begin(), o.shards.end());
    const OutputFolder folder(o.out, "--out", o.overwrite);
    mergeReferenceShards(shards, folder, o.quiet);
    return kExitOk;
}

namespace {

// One shard of a reference (ReferenceShards.h): its own folder, no report.json but shard.json.
int shardedReference(const ReferenceOptions& o) {
    const bool bySamples = !o.shard.empty();
    if (bySamples && !o.pathFrames.empty())
        throw InputError("--shard", "",
                         "splits one image by samples; --path-frames renders several frames "
                         "(split those with --frames-of)");
    if (!o.framesOf.empty() && o.pathFrames.empty())
        throw InputError("--frames-of", "", "needs --path-frames FIRST:LAST");
    if (!o.pathFrames.empty() && o.run.scene.camera.empty())
        throw InputError("--path-frames", "", "needs --camera (a camera path)");
    if (!o.pathFrames.empty() && o.pathFrame >= 0)
        throw InputError("--path-frames", "", "renders its own path frames; drop --path-frame");
    if (o.run.out.empty())
        throw InputError(bySamples ? "--shard" : "--path-frames", "",
                         "needs --out (each shard its own folder)");
    ShardRequest r;
    r.kind = bySamples ? "samples" : "frames";
    if (bySamples) r.shard = parseShard(o.shard, "--shard");
    if (!o.framesOf.empty()) r.shard = parseShard(o.framesOf, "--frames-of");
    if (!bySamples) r.pathFrames = parseFrameRange(o.pathFrames, "--path-frames");
    r.graphFile = o.run.graph.graph;
    r.desc = loadGraph(o.run.graph);
    const auto [width, height] = renderSize(o.run.graph, r.desc);
    r.width = width;
    r.height = height;
    r.seed = o.run.seed >= 0 ? uint64_t(o.run.seed) : r.desc.defaults.seed.value_or(0);
    r.spp = uint32_t(o.spp);
    r.pathFrame = o.run.fixedCameraFrame;
    r.key = shardKey(r, o.run.graph.sets, sceneOptionsKey(o.run.scene));
    shardFrames(r);  // an empty shard fails before the device exists
    checkOutputDir(o.run.out, "--out", o.run.overwrite);
    std::optional<gpu::Context> device;
    RunScene scene(o.run.scene, r.desc);
    scene.checkRenderSize(width, height);
    const OutputFolder folder(o.run.out, "--out", o.run.overwrite, kShardFile);
    gpu::Context& ctx = openDevice(device, o.run.device, o.run.validation, o.run.quiet);
    uploadScene(ctx, scene, o.run.quiet);
    renderReferenceShard(ctx, scene, r, folder, o.run.quiet);
    return kExitOk;
}

}  // namespace

int referenceCommand(ReferenceOptions o) {
    const fs::path defaultGraph = shippedGraph("reference.json");
    if (o.pixelCentres) {
        if (o.run.graph.graph != defaultGraph.string())
            throw InputError("--pixel-centres", "", "chooses the graph itself; drop --graph");
        o.run.graph.graph =
            shippedGraph("reference_pixel_centres.json");
    }
    if (o.pathFrame >= 0) {
        if (o.run.scene.camera.empty())
            throw InputError("--path-frame", "", "needs --camera (a camera path)");
        o.run.fixedCameraFrame = uint64_t(o.pathFrame);
    }
    if (!o.shard.empty() || !o.pathFrames.empty() || !o.framesOf.empty())
        return shardedReference(o);
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
