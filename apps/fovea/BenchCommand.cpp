// `fovea bench BENCH.json --out DIR`: runs every graph of a bench file on the same scene, camera
// path and size, measures GPU time per frame and per pass (medians over the frames after the
// warm-up) and the error of one output against a reference per frame, and writes tables and a
// run-time-vs-error plot (docs/bench.md).
#include <fstream>
#include <iostream>

#include "apps/fovea/Bench.h"
#include "apps/fovea/CliChecks.h"
#include "apps/fovea/Commands.h"
#include "apps/fovea/GraphRunner.h"
#include "apps/fovea/OutputFolder.h"
#include "apps/fovea/Progress.h"
#include "apps/fovea/ReferenceErrors.h"
#include "core/util/Error.h"
#include "core/vk/Context.h"

namespace fovea::app {

namespace fs = std::filesystem;
using nlohmann::json;

void addBenchCommand(CLI::App& app, BenchOptions& o) {
    auto* cmd = app.add_subcommand(
        "bench", "run several graphs and compare run time against error (docs/bench.md)");
    cmd->add_option("bench", o.file, "bench file (JSON)")->required();
    cmd->add_option("--out", o.out, "output directory for bench.json/.csv/.md/.svg")
        ->required()
        ->check(nonEmptyValue());
    cmd->add_option("--device", o.device, "GPU index or name substring (default: best available)")
        ->check(nonEmptyValue());
    cmd->add_flag("--validation", o.validation, "enable the Vulkan validation layer");
    cmd->add_flag("--overwrite", o.overwrite,
                  "allow writing into a non-empty output directory (a cached rendered reference "
                  "with the same settings is reused)");
    cmd->add_flag("--quiet", o.quiet, "no progress on stderr");
}

namespace {

SceneOptions sceneOptions(const BenchSpec& spec) {
    SceneOptions s;
    s.scene = spec.scene;
    s.camera = spec.camera;
    s.stereo = spec.stereo;
    s.mono = !spec.stereo;       // the bench decides, not the graphs' defaults
    s.ignoreGraphCamera = true;  // likewise the camera: the bench's path, else a still one
    return s;
}

graph::GraphDesc loadBenchGraph(const BenchSpec& spec, const std::string& file,
                                const std::vector<std::string>& sets, const std::string& pointer) {
    GraphOptions options;
    options.graph = file;
    options.sets = sets;
    try {
        return loadGraph(options);
    } catch (const InputError& e) {
        if (e.file().rfind("--set", 0) != 0) throw;  // the graph file's own error and pointer
        throw InputError(spec.file, pointer + "/set", e.what());
    }
}

// The rendered reference uses another seed than the measured runs: with the same one its first
// frames would repeat their samples, and its error against them would read too low.
uint64_t referenceSeed(uint64_t seed) {
    return seed + 1;
}

// The reference of the measured frames: the bench's file, or rendered once into DIR/reference
// (one image for a still camera, one per measured frame along a camera path) and reused while its
// settings (key.json) are unchanged.
fs::path prepareReference(const BenchSpec& spec, const OutputFolder& folder, gpu::Context& ctx,
                          bool quiet, json& info) {
    const fs::path& dir = folder.path();
    const BenchReference& ref = spec.reference;
    info = {{"source", ref.render ? "render" : "file"}};
    if (!ref.render) {
        info["path"] = ref.file;
        return ref.file;
    }
    graph::GraphDesc desc = loadBenchGraph(spec, ref.graph, ref.sets, "/reference/render");
    const json key = {{"graph", ref.graph},    {"set", ref.sets},
                      {"output", ref.output},  {"spp", ref.spp},
                      {"scene", spec.scene},   {"camera", spec.camera},
                      {"stereo", spec.stereo}, {"size", {spec.width, spec.height}},
                      {"seed", spec.seed},     {"frames", spec.frames},
                      {"warmup", spec.warmup}};
    const fs::path refDir = dir / "reference";
    const bool moving = !spec.camera.empty();
    const fs::path result = moving ? refDir : refDir / "reference.exr";
    info.update({{"path", result.string()}, {"spp", ref.spp}, {"graph", ref.graph}});
    json cached = json::parse(std::ifstream(refDir / "key.json"), nullptr, false);
    if (!cached.is_discarded() && cached == key && fs::exists(result)) {
        info["cached"] = true;
        return result;
    }
    fs::remove_all(refDir);
    fs::create_directories(refDir);
    SceneOptions so = sceneOptions(spec);
    for (uint32_t f = moving ? spec.warmup : 0; f < (moving ? spec.frames : 1u); ++f) {
        if (!quiet) std::cerr << "fovea: rendering the reference of frame " << f << "\n";
        RunScene scene(so, desc);
        uploadScene(ctx, scene, true);
        image::ImageRGBA img = renderReferenceImage(
            ctx, scene, desc, ref.graph, ref.spp,
            {spec.width, spec.height, referenceSeed(spec.seed), true, uint64_t(f)}, ref.output,
            spec.file + ": /reference/render/output", quiet);
        char name[32];
        std::snprintf(name, sizeof name, "frame%04u.exr", f);
        folder.write(
            moving ? "reference/" + std::string(name) : std::string("reference/reference.exr"),
            [&](const fs::path& path) { image::writeExr(path, img); });
    }
    // Written last and checked: a reference interrupted halfway is never taken as cached.
    folder.writeText("reference/key.json", key.dump(2) + "\n");
    info["cached"] = false;
    return result;
}

BenchResult runBenchGraph(const BenchSpec& spec, const BenchGraph& g, gpu::Context& ctx,
                          ReferenceSource& reference, bool quiet) {
    graph::GraphDesc desc = loadBenchGraph(spec, g.file, g.sets, g.pointer);
    RunScene scene(sceneOptions(spec), desc);
    uploadScene(ctx, scene, quiet);
    GraphRunner runner(ctx, scene, desc, {spec.width, spec.height, spec.seed, true, {}});
    BenchResult result;
    result.graph = g;
    const std::string pointer = g.output.empty() ? "/output" : g.pointer + "/output";
    result.output = selectComparedOutput(runner, g.output.empty() ? spec.output : g.output,
                                         spec.file + ": " + pointer);
    reference.choose(result.output);
    FrameErrors errors;
    std::vector<double> frameMs;
    std::vector<size_t> warmSamples;  // per node: gpuMs entries of the warm-up
    std::vector<uint64_t> warmExecutions;
    if (!quiet) std::cerr << "fovea: bench graph '" << g.label << "'\n";
    Progress progress(spec.frames, 0, quiet);
    for (uint32_t f = 0; f < spec.frames; ++f) {
        if (f == spec.warmup)
            for (const auto& rec : runner.graph().records()) {
                warmSamples.push_back(rec.gpuMs.size());
                warmExecutions.push_back(rec.executions);
            }
        graph::FrameTiming t = runner.runFrame();
        progress.update(f + 1);
        if (f < spec.warmup) continue;
        frameMs.push_back(t.gpuMs);
        errors.add(f, runner.download(result.output),
                   g.label + " " + result.output + " frame " + std::to_string(f),
                   reference.forFrame(f), reference.fileFor(f).string(), &runner.graph().camera());
    }
    progress.finish();
    result.frameMs = computeStats(frameMs);
    result.meanErrors = errors.mean();
    result.temporalError = errors.temporalError();
    result.errors = errors.json();
    const auto& plan = runner.graph().plan();
    for (size_t n = 0; n < plan.nodes.size(); ++n) {
        const auto& rec = runner.graph().records()[n];
        BenchPass p;
        p.name = plan.nodes[n].name;
        p.type = plan.nodes[n].type;
        p.status = graph::passStatusName(rec.status);
        // Records exist from build on; the guards only keep a graph without them from crashing.
        const size_t skip = n < warmSamples.size() ? warmSamples[n] : 0;
        p.gpuMs = computeStats(
            {rec.gpuMs.begin() + long(std::min(skip, rec.gpuMs.size())), rec.gpuMs.end()});
        p.executions = rec.executions - (n < warmExecutions.size() ? warmExecutions[n] : 0);
        result.passes.push_back(p);
    }
    return result;
}

}  // namespace

int benchCommand(const BenchOptions& o) {
    const BenchSpec spec = parseBenchFile(o.file);
    const fs::path dir = o.out;
    checkOutputDir(dir, "--out", o.overwrite);
    // Every graph file and --set is checked before the device exists (fail fast).
    for (const auto& g : spec.graphs) loadBenchGraph(spec, g.file, g.sets, g.pointer);
    std::optional<ReferenceSource> fileReference;
    if (!spec.reference.render) {
        fileReference.emplace(spec.reference.file, spec.file + ": /reference", spec.width,
                              spec.height);
        fileReference->requireFrames(spec.warmup, spec.frames - 1);
    }
    // Taken like `fovea run`'s folder (OutputFolder.h): locked, emptiness re-checked under the
    // lock, every file written checked under a temporary name, bench.json last with "finished".
    const OutputFolder folder(dir, "--out", o.overwrite, "bench.json");
    std::optional<gpu::Context> device;
    gpu::Context& ctx = openDevice(device, o.device, o.validation, o.quiet);
    json referenceInfo;
    const fs::path refPath = prepareReference(spec, folder, ctx, o.quiet, referenceInfo);
    ReferenceSource reference = fileReference ? std::move(*fileReference)
                                              : ReferenceSource(refPath, spec.file + ": /reference",
                                                                spec.width, spec.height);
    reference.requireFrames(spec.warmup, spec.frames - 1);
    referenceInfo["mode"] = reference.perFrame() ? "per-frame" : "single";

    std::vector<BenchResult> results;
    for (const auto& g : spec.graphs)
        results.push_back(runBenchGraph(spec, g, ctx, reference, o.quiet));
    checkValidation(ctx);
    const double baseline = results.front().frameMs.median;
    for (auto& r : results) r.speedup = r.frameMs.median > 0 ? baseline / r.frameMs.median : 0.0;

    const json header = {
        {"bench_version", 1},
        {"fovea_version", FOVEA_VERSION},
        {"bench", spec.file},
        {"name", spec.name},
        {"device",
         {{"name", ctx.deviceName()}, {"driver", ctx.driverName() + " " + ctx.driverInfo()}}},
        {"scene", spec.scene},
        {"camera", spec.camera.empty() ? json("still") : json(spec.camera)},
        {"stereo", spec.stereo},
        {"size", {spec.width, spec.height}},
        {"frames", spec.frames},
        {"warmup", spec.warmup},
        {"seed", spec.seed},
        {"reference", referenceInfo}};
    folder.writeText("bench.svg", benchPlotSvg(results, spec.name + " — " + ctx.deviceName()));
    std::string why;
    bool rasterized = true;
    try {
        folder.write("bench.png", [&](const fs::path& path) {
            rasterized = rasterizeSvg(dir / "bench.svg", path, why);
            if (!rasterized) throw RuntimeError(why);  // removes the temporary file
        });
    } catch (const RuntimeError&) {
        if (rasterized) throw;  // the rename failed: a write error like any other
        if (!o.quiet) std::cerr << "fovea: bench.png not written: " << why << "\n";
    }
    writeBenchTables(folder, header, results);
    if (!o.quiet) std::cerr << "fovea: wrote " << (dir / "bench.md").string() << "\n";
    return kExitOk;
}

}  // namespace fovea::app
