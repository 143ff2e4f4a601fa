// The work items of a bench (BenchRunner.h): the plan, the rendered references and one graph run
// with one seed. Combining their results is BenchCollect.cpp.
#include "eval/bench/BenchRunner.h"

#include <algorithm>
#include <fstream>
#include <iostream>

#include "core/util/Error.h"
#include "core/util/Hash.h"
#include "core/vk/Context.h"
#include "eval/reference/ReferenceRender.h"
#include "eval/report/OutputFolder.h"
#include "eval/run/GraphLoading.h"
#include "eval/run/GraphRunner.h"
#include "eval/run/Progress.h"

namespace fovea::eval {

namespace fs = std::filesystem;
using nlohmann::json;

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
uint64_t referenceSeed(const BenchSpec& spec, bool noiseFloor) {
    return *std::max_element(spec.seeds.begin(), spec.seeds.end()) + (noiseFloor ? 2 : 1);
}

const char* folderOf(bool noiseFloor) {
    return noiseFloor ? "reference_noise_floor" : "reference";
}

// The settings a rendered reference depends on: it is reused while its key.json equals them.
json referenceKey(const BenchSpec& spec, bool noiseFloor) {
    const BenchReference& ref = spec.reference;
    json key = {{"graph", ref.graph},
                {"set", ref.sets},
                {"output", ref.output},
                {"spp", ref.spp},
                {"scene", spec.scene},
                {"camera", spec.camera},
                {"stereo", spec.stereo},
                {"size", {spec.width, spec.height}},
                {"seed", referenceSeed(spec, noiseFloor)},
                {"frames", spec.frames},
                {"sun", spec.sun},
                {"warmup", spec.warmup}};
    // Only when set: the keys of references cached before camera models existed stay valid.
    if (!spec.cameraModel.empty()) key["camera_model"] = spec.cameraModel;
    // Only with an environment: the keys of references cached before `env` existed stay valid.
    if (!spec.env.empty()) key["env"] = environmentKey(sceneOptions(spec));
    return key;
}

// A still camera's reference is one image; a camera path's a folder of one EXR per measured frame.
fs::path renderedReferencePath(const BenchSpec& spec, const fs::path& dir, bool noiseFloor) {
    const fs::path refDir = dir / folderOf(noiseFloor);
    return spec.camera.empty() ? refDir / "reference.exr" : refDir;
}

bool referenceIsCurrent(const BenchSpec& spec, const fs::path& dir, bool noiseFloor) {
    const fs::path refDir = dir / folderOf(noiseFloor);
    const json cached = json::parse(std::ifstream(refDir / "key.json"), nullptr, false);
    return !cached.is_discarded() && cached == referenceKey(spec, noiseFloor) &&
           fs::exists(renderedReferencePath(spec, dir, noiseFloor));
}

// The reference (or its noise floor) of the measured frames, rendered into its folder unless the
// folder already holds it (key.json unchanged). Returns its "reference" info of bench.json.
json renderReference(const BenchSpec& spec, const fs::path& dir, bool noiseFloor, gpu::Context& ctx,
                     bool quiet) {
    const BenchReference& ref = spec.reference;
    const uint64_t seed = referenceSeed(spec, noiseFloor);
    json info = {
        {"source", "render"}, {"path", renderedReferencePath(spec, dir, noiseFloor).string()},
        {"spp", ref.spp},     {"graph", ref.graph},
        {"seed", seed},       {"cached", true}};
    if (referenceIsCurrent(spec, dir, noiseFloor)) return info;
    info["cached"] = false;
    graph::GraphDesc desc = loadBenchGraph(spec, ref.graph, ref.sets, "/reference/render");
    // Its own folder, locked: two items of one bench never render into the same one. key.json
    // goes first (the folder's report) and comes back last, so an interrupted render never reads
    // as current; what an older key left there is removed.
    const OutputFolder folder(dir / folderOf(noiseFloor), "--out", true, "key.json");
    for (const auto& entry : fs::directory_iterator(folder.path()))
        if (entry.path().filename() != kOutputLockName) fs::remove_all(entry.path());
    const bool moving = !spec.camera.empty();
    SceneOptions so = sceneOptions(spec);
    for (uint32_t f = moving ? spec.warmup : 0; f < (moving ? spec.frames : 1u); ++f) {
        if (!quiet)
            std::cerr << "fovea: rendering the " << (noiseFloor ? "noise floor" : "reference")
                      << " of frame " << f << "\n";
        RunScene scene(so, desc);
        uploadScene(ctx, scene, true);
        image::ImageRGBA img =
            renderReferenceImage(ctx, scene, desc, ref.graph, ref.spp,
                                 {spec.width, spec.height, seed, true, uint64_t(f)}, ref.output,
                                 spec.file + ": /reference/render/output", quiet);
        char name[32];
        std::snprintf(name, sizeof name, "frame%04u.exr", f);
        folder.write(moving ? std::string(name) : std::string("reference.exr"),
                     [&](const fs::path& path) { image::writeExr(path, img); });
    }
    folder.writeText("key.json", referenceKey(spec, noiseFloor).dump(2) + "\n");
    return info;
}

// The references one output is measured against: the bench's own and BenchSpec::against, each
// with an optional second reference of another seed (its noise floor).
struct MeasuredReference {
    std::string label;
    ReferenceSource source;
    std::optional<ReferenceSource> second;
};

ReferenceSource referenceSource(const BenchSpec& spec, const std::string& path,
                                const std::string& pointer) {
    ReferenceSource r(path, spec.file + ": " + pointer, spec.width, spec.height);
    r.requireFrames(spec.warmup, spec.frames - 1);
    return r;
}

// A rendered reference a run reads must be there and current; else the run says which item
// renders it.
std::string renderedReference(const BenchSpec& spec, const fs::path& dir, bool noiseFloor) {
    if (!referenceIsCurrent(spec, dir, noiseFloor))
        throw InputError("--item", "",
                         "the " + std::string(noiseFloor ? "noise floor" : "reference") + " in '" +
                             (dir / folderOf(noiseFloor)).string() +
                             "' is missing or was rendered for other " + "settings: run item " +
                             (noiseFloor ? "noise_floor" : "reference") +
                             " of `fovea bench --plan` first");
    return renderedReferencePath(spec, dir, noiseFloor).string();
}

std::vector<MeasuredReference> measuredReferences(const BenchSpec& spec, const fs::path& dir) {
    std::vector<MeasuredReference> references;
    const std::string main =
        spec.reference.render ? renderedReference(spec, dir, false) : spec.reference.file;
    references.push_back({"reference", referenceSource(spec, main, "/reference"), std::nullopt});
    if (spec.noiseFloorRender)
        references[0].second.emplace(
            referenceSource(spec, renderedReference(spec, dir, true), "/noise_floor"));
    else if (!spec.noiseFloor.empty())
        references[0].second.emplace(referenceSource(spec, spec.noiseFloor, "/noise_floor"));
    for (const auto& a : spec.against) {
        MeasuredReference m{a.label, referenceSource(spec, a.file, a.pointer + "/reference"),
                            std::nullopt};
        if (!a.noiseFloor.empty())
            m.second.emplace(referenceSource(spec, a.noiseFloor, a.pointer + "/noise_floor"));
        references.push_back(std::move(m));
    }
    return references;
}

// One run of one graph with one seed: its frame times, errors per reference, per-pass GPU times
// over the measured frames and, with `floors`, each second reference against its first (measured
// once per bench, with the first graph and seed).
json runGraphSeed(const BenchSpec& spec, const BenchGraph& g, uint64_t seed, const fs::path& dir,
                  gpu::Context& ctx, bool floors, bool quiet) {
    std::vector<MeasuredReference> references = measuredReferences(spec, dir);
    const std::optional<LayerRadii> layers = benchLayerRadii(spec);
    graph::GraphDesc desc = loadBenchGraph(spec, g.file, g.sets, g.pointer);
    RunScene scene(sceneOptions(spec), desc);
    uploadScene(ctx, scene, quiet);
    GraphRunner runner(ctx, scene, desc, {spec.width, spec.height, seed, true, {}});
    const std::string pointer = g.output.empty() ? "/output" : g.pointer + "/output";
    const std::string output = selectComparedOutput(
        runner, g.output.empty() ? spec.output : g.output, spec.file + ": " + pointer);
    for (auto& m : references) {
        m.source.choose(output);
        if (m.second) m.second->choose(output);
    }
    // Every error track (and the noise floors) splits by the same layers and scores ꟻLIP alike.
    const bool displayEncoded = runner.displayEncoded(output);
    std::vector<FrameErrors> errors(references.size()), floorErrors(references.size());
    for (auto* track : {&errors, &floorErrors})
        for (auto& e : *track) {
            if (layers) e.setLayers(*layers);
            e.setFlip(spec.flip, displayEncoded);
        }
    std::vector<size_t> warmSamples;  // per node: gpuMs entries of the warm-up
    std::vector<uint64_t> warmExecutions;
    if (!quiet)
        std::cerr << "fovea: bench graph '" << g.label << "'"
                  << (spec.seeds.size() > 1 ? ", seed " + std::to_string(seed) : "") << "\n";
    Progress progress(spec.frames, 0, quiet);
    std::vector<double> frameMs;
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
        const image::ImageRGBA image = runner.download(output);
        const auto* camera = &runner.graph().camera();
        for (size_t i = 0; i < references.size(); ++i) {
            MeasuredReference& m = references[i];
            errors[i].add(f, image, g.label + " " + output + " frame " + std::to_string(f),
                          m.source.forFrame(f), m.source.fileFor(f).string(), camera);
            if (floors && m.second)
                floorErrors[i].add(f, m.second->forFrame(f), m.second->fileFor(f).string(),
                                   m.source.forFrame(f), m.source.fileFor(f).string(), camera);
        }
    }
    progress.finish();
    json result = {
        {"kind", "run"},
        {"graph", g.label},
        {"seed", seed},
        {"output", output},
        {"device",
         {{"name", ctx.deviceName()}, {"driver", ctx.driverName() + " " + ctx.driverInfo()}}},
        {"reference_mode", references[0].source.perFrame() ? "per-frame" : "single"},
        {"env", spec.env.empty() ? json() : environmentKey(sceneOptions(spec))},
        {"frame_ms", frameMs},
        {"tracks", json::array()},
        {"passes", json::array()}};
    for (size_t i = 0; i < references.size(); ++i)
        result["tracks"].push_back({{"label", references[i].label},
                                    {"mean", metricsToJson(errors[i].mean(), {})},
                                    {"errors", errors[i].json()}});
    if (floors) {
        result["noise_floors"] = json::object();
        for (size_t i = 0; i < references.size(); ++i)
            if (references[i].second)
                result["noise_floors"][references[i].label] = floorErrors[i].json();
    }
    const auto& plan = runner.graph().plan();
    for (size_t n = 0; n < plan.nodes.size(); ++n) {
        const auto& rec = runner.graph().records()[n];
        // Records exist from build on; the guards only keep a graph without them from crashing.
        const size_t skip = std::min(n < warmSamples.size() ? warmSamples[n] : 0, rec.gpuMs.size());
        result["passes"].push_back(
            {{"name", plan.nodes[n].name},
             {"type", plan.nodes[n].type},
             {"status", graph::passStatusName(rec.status)},
             {"executions", rec.executions - (n < warmExecutions.size() ? warmExecutions[n] : 0)},
             {"ms", std::vector<double>(rec.gpuMs.begin() + long(skip), rec.gpuMs.end())}});
    }
    checkValidation(ctx);
    return result;
}

}  // namespace

std::vector<BenchItem> benchPlan(const BenchSpec& spec) {
    std::vector<BenchItem> items;
    if (spec.reference.render) items.push_back({BenchItem::Kind::Reference, 0, 0, "reference"});
    if (spec.noiseFloorRender) items.push_back({BenchItem::Kind::NoiseFloor, 0, 0, "noise_floor"});
    // Seed-major: every graph's run with the first seed, then every graph's with the next, so
    // that a slow spell of a shared machine falls on all graphs alike (the seeds are interleaved
    // repeats of the comparison) instead of on the one graph running at the time.
    for (size_t s = 0; s < spec.seeds.size(); ++s)
        for (size_t g = 0; g < spec.graphs.size(); ++g)
            items.push_back(
                {BenchItem::Kind::Run, g, s, "g" + std::to_string(g) + "_s" + std::to_string(s)});
    return items;
}

fs::path benchItemResult(const BenchItem& item) {
    return fs::path("items") / item.name / "result.json";
}

std::string benchKey(const BenchSpec& spec) {
    // The file as parsed JSON (formatting and key order do not matter), with the version: a result
    // of another bench file or another fovea is refused, not mixed in.
    const json file = json::parse(std::ifstream(spec.file), nullptr, false);
    return fnv1aHex(file.dump() + "\n" + FOVEA_VERSION);
}

json benchPlanJson(const BenchSpec& spec) {
    json items = json::array();
    const std::vector<BenchItem> plan = benchPlan(spec);
    json references = json::array();  // what every run reads
    for (size_t i = 0; i < plan.size(); ++i) {
        const BenchItem& item = plan[i];
        json j = {{"index", i}, {"name", item.name}, {"result", benchItemResult(item).string()}};
        if (item.kind != BenchItem::Kind::Run) {
            j["kind"] = item.kind == BenchItem::Kind::Reference ? "reference" : "noise_floor";
            j["needs"] = json::array();
            references.push_back(i);
        } else {
            j["kind"] = "run";
            j["needs"] = references;
            j["graph"] = spec.graphs[item.graph].label;
            j["graph_index"] = item.graph;
            j["seed"] = spec.seeds[item.seed];
        }
        items.push_back(std::move(j));
    }
    return {{"bench", spec.file}, {"bench_key", benchKey(spec)}, {"items", items}};
}

std::optional<LayerRadii> checkBenchInputs(const BenchSpec& spec) {
    for (const auto& g : spec.graphs) loadBenchGraph(spec, g.file, g.sets, g.pointer);
    if (spec.reference.render)
        loadBenchGraph(spec, spec.reference.graph, spec.reference.sets, "/reference/render");
    if (!spec.reference.render) referenceSource(spec, spec.reference.file, "/reference");
    if (!spec.noiseFloor.empty()) referenceSource(spec, spec.noiseFloor, "/noise_floor");
    for (const auto& a : spec.against) {
        referenceSource(spec, a.file, a.pointer + "/reference");
        if (!a.noiseFloor.empty()) referenceSource(spec, a.noiseFloor, a.pointer + "/noise_floor");
    }
    return benchLayerRadii(spec);
}

std::optional<LayerRadii> benchLayerRadii(const BenchSpec& spec) {
    // The FoveationMask facts (after --set) of the first graph that has one; none when none has.
    if (spec.layers) return spec.layers;
    for (const auto& g : spec.graphs)
        if (auto radii = foveationRadiiOf(loadBenchGraph(spec, g.file, g.sets, g.pointer)))
            return radii;
    return std::nullopt;
}

json runBenchItem(const BenchSpec& spec, const BenchItem& item, const fs::path& dir,
                  gpu::Context& ctx, bool quiet) {
    json result;
    if (item.kind == BenchItem::Kind::Run) {
        const bool floors = item.graph == 0 && item.seed == 0;
        result = runGraphSeed(spec, spec.graphs[item.graph], spec.seeds[item.seed], dir, ctx,
                              floors, quiet);
        result["graph_index"] = item.graph;
    } else {
        const bool noiseFloor = item.kind == BenchItem::Kind::NoiseFloor;
        result = {{"kind", noiseFloor ? "noise_floor" : "reference"},
                  {"info", renderReference(spec, dir, noiseFloor, ctx, quiet)}};
        checkValidation(ctx);
    }
    result["item"] = item.name;
    result["bench_key"] = benchKey(spec);
    return result;
}

}  // namespace fovea::eval
