// `fovea bench BENCH.json --out DIR`: runs every graph of a bench file on the same scene, camera
// path and size, measures GPU time per frame and per pass (medians over the frames after the
// warm-up) and the error of one output against a reference per frame, and writes tables and a
// run-time-vs-error plot (docs/bench.md).
#include <algorithm>
#include <fstream>
#include <iostream>

#include "apps/fovea/CliChecks.h"
#include "apps/fovea/Commands.h"
#include "core/util/Error.h"
#include "core/vk/Context.h"
#include "eval/bench/Bench.h"
#include "eval/reference/ReferenceErrors.h"
#include "eval/reference/ReferenceRender.h"
#include "eval/report/OutputFolder.h"
#include "eval/run/GraphRunner.h"
#include "eval/run/Progress.h"

namespace fovea::app {

namespace fs = std::filesystem;
using nlohmann::json;

void addBenchCommand(CLI::App& app, BenchOptions& o) {
    auto* cmd = app.add_subcommand(
        "bench", "run several graphs and compare run time against error (docs/bench.md)");
    cmd->add_option("bench", o.file, "bench file (JSON)")->required()->check(userPath());
    cmd->add_option("--out", o.out, "output directory for bench.json/.csv/.md/.svg")
        ->required()
        ->check(nonEmptyValue())
        ->check(userPath());
    cmd->add_option("--device", o.device, "GPU index or name substring (default: best available)")
        ->check(nonEmptyValue());
    cmd->add_option("--camera-model", o.cameraModel,
                    "perspective or equirect (360°, 2:1 sizes), overriding the bench file's "
                    "camera_model")
        ->check(CLI::IsMember({"perspective", "equirect"}));
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
    s.mono = !spec.stereo;  // the bench decides, not the graphs' defaults
    s.cameraModel = spec.cameraModel;
    s.sun = spec.sun;
    s.env = spec.env;
    s.envIntensity = spec.envIntensity;
    s.envRotation = spec.envRotation;
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
// frames would repeat their samples, and its error against them would read too low. The second
// reference of the noise floor uses a third seed.
// With several run seeds both follow the largest, so that neither equals any run seed.
uint64_t referenceSeed(const std::vector<uint64_t>& seeds) {
    return *std::max_element(seeds.begin(), seeds.end()) + 1;
}
uint64_t noiseFloorSeed(const std::vector<uint64_t>& seeds) {
    return *std::max_element(seeds.begin(), seeds.end()) + 2;
}

// The reference of the measured frames: the bench's file, or rendered once into DIR/reference
// (one image for a still camera, one per measured frame along a camera path) and reused while its
// settings (key.json) are unchanged.
fs::path prepareReference(const BenchSpec& spec, const OutputFolder& out, const std::string& folder,
                          uint64_t seed, gpu::Context& ctx, bool quiet, json& info) {
    const fs::path& dir = out.path();
    const BenchReference& ref = spec.reference;
    info = {{"source", ref.render ? "render" : "file"}};
    if (!ref.render) {
        info["path"] = ref.file;
        return ref.file;
    }
    graph::GraphDesc desc = loadBenchGraph(spec, ref.graph, ref.sets, "/reference/render");
    json key = {{"graph", ref.graph},    {"set", ref.sets},
                {"output", ref.output},  {"spp", ref.spp},
                {"scene", spec.scene},   {"camera", spec.camera},
                {"stereo", spec.stereo}, {"size", {spec.width, spec.height}},
                {"seed", seed},          {"frames", spec.frames},
                {"sun", spec.sun},       {"warmup", spec.warmup}};
    // Only when set: the keys of references cached before camera models existed stay valid.
    if (!spec.cameraModel.empty()) key["camera_model"] = spec.cameraModel;
    // Only with an environment: the keys of references cached before `env` existed stay valid.
    if (!spec.env.empty()) key["env"] = environmentKey(sceneOptions(spec));
    const fs::path refDir = dir / folder;
    const bool moving = !spec.camera.empty();
    const fs::path result = moving ? refDir : refDir / "reference.exr";
    info.update(
        {{"path", result.string()}, {"spp", ref.spp}, {"graph", ref.graph}, {"seed", seed}});
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
        image::ImageRGBA img =
            renderReferenceImage(ctx, scene, desc, ref.graph, ref.spp,
                                 {spec.width, spec.height, seed, true, uint64_t(f)}, ref.output,
                                 spec.file + ": /reference/render/output", quiet);
        char name[32];
        std::snprintf(name, sizeof name, "frame%04u.exr", f);
        out.write(folder + "/" + (moving ? std::string(name) : std::string("reference.exr")),
                  [&](const fs::path& path) { image::writeExr(path, img); });
    }
    // Written last and checked: a reference interrupted halfway is never taken as cached.
    out.writeText(folder + "/key.json", key.dump(2) + "\n");
    info["cached"] = false;
    return result;
}

// The references one output is measured against: the bench's own and BenchSpec::against, each
// with an optional second reference of another seed (its noise floor).
struct MeasuredReference {
    std::string label;
    ReferenceSource source;
    std::optional<ReferenceSource> second;
};

// The radii of the per-layer errors: the bench's "layers", else the FoveationMask parameters
// (after --set) of the first graph that has one; none when no graph has.
std::optional<eval::LayerRadii> layerRadii(const BenchSpec& spec) {
    if (spec.layers) return spec.layers;
    for (const auto& g : spec.graphs)
        if (auto radii = foveationRadiiOf(loadBenchGraph(spec, g.file, g.sets, g.pointer)))
            return radii;
    return std::nullopt;
}

// One run of one graph with one seed: its frame times, errors per reference and per-pass GPU
// times over the measured frames.
struct SeedRun {
    std::string output;
    std::vector<double> frameMs;
    std::vector<FrameErrors> errors;  // one per reference
    std::vector<BenchPass> passes;    // gpuMs unset: the samples are in passMs
    std::vector<std::vector<double>> passMs;
};

SeedRun runBenchSeed(const BenchSpec& spec, const BenchGraph& g, uint64_t seed, gpu::Context& ctx,
                     std::vector<MeasuredReference>& references,
                     const std::optional<eval::LayerRadii>& layers,
                     std::vector<FrameErrors>* floors, bool quiet) {
    graph::GraphDesc desc = loadBenchGraph(spec, g.file, g.sets, g.pointer);
    RunScene scene(sceneOptions(spec), desc);
    uploadScene(ctx, scene, quiet);
    GraphRunner runner(ctx, scene, desc, {spec.width, spec.height, seed, true, {}});
    SeedRun run;
    const std::string pointer = g.output.empty() ? "/output" : g.pointer + "/output";
    run.output = selectComparedOutput(runner, g.output.empty() ? spec.output : g.output,
                                      spec.file + ": " + pointer);
    for (auto& m : references) {
        m.source.choose(run.output);
        if (m.second) m.second->choose(run.output);
    }
    // Every error track (and the noise floors) splits by the same layers and scores ꟻLIP alike.
    const bool displayEncoded = runner.displayEncoded(run.output);
    auto tracks = [&](std::vector<FrameErrors>& errors) {
        errors.assign(references.size(), FrameErrors());
        for (auto& e : errors) {
            if (layers) e.setLayers(*layers);
            e.setFlip(spec.flip, displayEncoded);
        }
    };
    tracks(run.errors);
    if (floors) tracks(*floors);
    std::vector<size_t> warmSamples;  // per node: gpuMs entries of the warm-up
    std::vector<uint64_t> warmExecutions;
    if (!quiet)
        std::cerr << "fovea: bench graph '" << g.label << "'"
                  << (spec.seeds.size() > 1 ? ", seed " + std::to_string(seed) : "") << "\n";
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
        run.frameMs.push_back(t.gpuMs);
        const image::ImageRGBA image = runner.download(run.output);
        const auto* camera = &runner.graph().camera();
        for (size_t i = 0; i < references.size(); ++i) {
            MeasuredReference& m = references[i];
            run.errors[i].add(f, image, g.label + " " + run.output + " frame " + std::to_string(f),
                              m.source.forFrame(f), m.source.fileFor(f).string(), camera);
            // The floor: the second reference against the first, on the same frame and camera
            // (measured once per bench, with the first graph and seed).
            if (floors && m.second)
                (*floors)[i].add(f, m.second->forFrame(f), m.second->fileFor(f).string(),
                                 m.source.forFrame(f), m.source.fileFor(f).string(), camera);
        }
    }
    progress.finish();
    const auto& plan = runner.graph().plan();
    for (size_t n = 0; n < plan.nodes.size(); ++n) {
        const auto& rec = runner.graph().records()[n];
        BenchPass p;
        p.name = plan.nodes[n].name;
        p.type = plan.nodes[n].type;
        p.status = graph::passStatusName(rec.status);
        // Records exist from build on; the guards only keep a graph without them from crashing.
        const size_t skip = n < warmSamples.size() ? warmSamples[n] : 0;
        run.passMs.emplace_back(rec.gpuMs.begin() + long(std::min(skip, rec.gpuMs.size())),
                                rec.gpuMs.end());
        p.executions = rec.executions - (n < warmExecutions.size() ? warmExecutions[n] : 0);
        run.passes.push_back(p);
    }
    return run;
}

// Every seed's run of one graph: times over the measured frames of all seeds; errors of one seed
// as FrameErrors gives them, of several the means over the seeds (combineSeedErrors).
BenchResult runBenchGraph(const BenchSpec& spec, const BenchGraph& g, gpu::Context& ctx,
                          std::vector<MeasuredReference>& references,
                          const std::optional<eval::LayerRadii>& layers,
                          std::vector<FrameErrors>* floors, bool quiet) {
    std::vector<SeedRun> runs;
    for (size_t s = 0; s < spec.seeds.size(); ++s)
        runs.push_back(runBenchSeed(spec, g, spec.seeds[s], ctx, references, layers,
                                    s == 0 ? floors : nullptr, quiet));
    BenchResult result;
    result.graph = g;
    result.output = runs.front().output;
    std::vector<double> frameMs;
    for (const auto& run : runs)
        frameMs.insert(frameMs.end(), run.frameMs.begin(), run.frameMs.end());
    result.frameMs = computeStats(frameMs);
    // The same graph every seed: the same passes in the same order.
    result.passes = runs.back().passes;
    for (size_t n = 0; n < result.passes.size(); ++n) {
        std::vector<double> ms;
        uint64_t executions = 0;
        for (const auto& run : runs) {
            ms.insert(ms.end(), run.passMs[n].begin(), run.passMs[n].end());
            executions += run.passes[n].executions;
        }
        result.passes[n].gpuMs = computeStats(ms);
        result.passes[n].executions = executions;
    }
    for (size_t i = 0; i < references.size(); ++i) {
        BenchTrack track{references[i].label, {}, {}};
        if (runs.size() == 1) {
            track.meanErrors = runs[0].errors[i].mean();
            track.errors = runs[0].errors[i].json();
        } else {
            std::vector<eval::ImageMetrics> means;
            std::vector<json> perSeed;
            for (const auto& run : runs) {
                means.push_back(run.errors[i].mean());
                perSeed.push_back(run.errors[i].json());
            }
            track.meanErrors = meanOverSeeds(means);
            track.errors = combineSeedErrors(spec.seeds, perSeed);
        }
        if (i > 0) {
            result.against.push_back(std::move(track));
            continue;
        }
        result.meanErrors = track.meanErrors;
        result.errors = track.errors;
        result.temporalError = track.errors.at("temporal_error").get<double>();
    }
    return result;
}

}  // namespace

int benchCommand(const BenchOptions& o) {
    BenchSpec spec = parseBenchFile(o.file);
    if (!o.cameraModel.empty()) {
        spec.cameraModel = o.cameraModel;
        if (o.cameraModel == "equirect" && spec.width != 2 * spec.height)
            throw InputError("--camera-model", "",
                             "an equirect camera needs a 2:1 image; " + spec.file + ": /size is " +
                                 std::to_string(spec.width) + "x" + std::to_string(spec.height));
    }
    const fs::path dir = o.out;
    checkOutputDir(dir, "--out", o.overwrite);
    // Every graph file and --set is checked before the device exists (fail fast).
    for (const auto& g : spec.graphs) loadBenchGraph(spec, g.file, g.sets, g.pointer);
    const std::optional<eval::LayerRadii> layers = layerRadii(spec);
    // File references are read and checked before the device exists too.
    auto source = [&](const std::string& path, const std::string& pointer) {
        ReferenceSource r(path, spec.file + ": " + pointer, spec.width, spec.height);
        r.requireFrames(spec.warmup, spec.frames - 1);
        return r;
    };
    std::optional<ReferenceSource> fileReference, fileFloor;
    if (!spec.reference.render) fileReference.emplace(source(spec.reference.file, "/reference"));
    if (!spec.noiseFloor.empty()) fileFloor.emplace(source(spec.noiseFloor, "/noise_floor"));
    std::vector<MeasuredReference> against;
    for (const auto& a : spec.against) {
        MeasuredReference m{a.label, source(a.file, a.pointer + "/reference"), std::nullopt};
        if (!a.noiseFloor.empty())
            m.second.emplace(source(a.noiseFloor, a.pointer + "/noise_floor"));
        against.push_back(std::move(m));
    }
    // Taken like `fovea run`'s folder (OutputFolder.h): locked, emptiness re-checked under the
    // lock, every file written checked under a temporary name, bench.json last with "finished".
    const OutputFolder folder(dir, "--out", o.overwrite, "bench.json");
    std::optional<gpu::Context> device;
    gpu::Context& ctx = openDevice(device, o.device, o.validation, o.quiet);
    json referenceInfo, floorInfo;
    const fs::path refPath = prepareReference(spec, folder, "reference", referenceSeed(spec.seeds),
                                              ctx, o.quiet, referenceInfo);
    std::vector<MeasuredReference> references;
    references.push_back(
        {"reference",
         fileReference ? std::move(*fileReference) : source(refPath.string(), "/reference"),
         std::nullopt});
    for (auto& m : against) references.push_back(std::move(m));
    referenceInfo["mode"] = references[0].source.perFrame() ? "per-frame" : "single";
    if (spec.noiseFloorRender) {
        const fs::path floorPath =
            prepareReference(spec, folder, "reference_noise_floor", noiseFloorSeed(spec.seeds), ctx,
                             o.quiet, floorInfo);
        references[0].second.emplace(source(floorPath.string(), "/noise_floor"));
    } else if (fileFloor) {
        references[0].second = std::move(fileFloor);
        floorInfo = {{"source", "file"}, {"path", spec.noiseFloor}};
    }
    if (!floorInfo.is_null()) referenceInfo["noise_floor"] = floorInfo;

    std::vector<BenchResult> results;
    std::vector<FrameErrors> floors;
    for (size_t i = 0; i < spec.graphs.size(); ++i)
        results.push_back(runBenchGraph(spec, spec.graphs[i], ctx, references, layers,
                                        i == 0 ? &floors : nullptr, o.quiet));
    checkValidation(ctx);
    const double baseline = results.front().frameMs.median;
    for (auto& r : results) r.speedup = r.frameMs.median > 0 ? baseline / r.frameMs.median : 0.0;
    std::vector<double> ms, rmse;
    for (const auto& r : results) {
        ms.push_back(r.frameMs.median);
        rmse.push_back(r.meanErrors.rmsePercent);
    }
    const std::vector<bool> pareto = eval::paretoOptimal(ms, rmse);
    for (size_t i = 0; i < results.size(); ++i) results[i].pareto = pareto[i];
    if (spec.seeds.size() > 1)
        for (size_t i = 1; i < results.size(); ++i)
            results[i].difference =
                pairedDifference(results[i].errors, results[0].errors, results[0].graph.label);
    json noiseFloor = json::object();
    for (size_t i = 0; i < references.size() && i < floors.size(); ++i)
        if (references[i].second) noiseFloor[references[i].label] = floors[i].json();

    json header = {
        {"bench_version", 1},
        {"fovea_version", FOVEA_VERSION},
        {"bench", spec.file},
        {"name", spec.name},
        {"device",
         {{"name", ctx.deviceName()}, {"driver", ctx.driverName() + " " + ctx.driverInfo()}}},
        {"scene", spec.scene},
        {"camera", spec.camera.empty() ? json("still") : json(spec.camera)},
        {"stereo", spec.stereo},
        {"camera_model", spec.cameraModel.empty() ? "graph" : spec.cameraModel},
        {"sun", spec.sun},
        {"size", {spec.width, spec.height}},
        {"frames", spec.frames},
        {"warmup", spec.warmup},
        {"seed", spec.seeds.front()},
        {"reference", referenceInfo}};
    if (!spec.env.empty()) header["env"] = environmentKey(sceneOptions(spec));
    if (spec.seeds.size() > 1) header["seeds"] = spec.seeds;
    if (!noiseFloor.empty()) header["noise_floor"] = noiseFloor;
    if (layers)
        header["layers"] = {{"r0", layers->r0},
                            {"r1", layers->r1},
                            {"unit", layers->degrees ? "degrees" : "pixels"}};
    if (!spec.against.empty()) {
        header["also_against"] = json::array();
        for (const auto& a : spec.against)
            header["also_against"].push_back(
                {{"label", a.label}, {"path", a.file}, {"noise_floor", a.noiseFloor}});
    }
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
