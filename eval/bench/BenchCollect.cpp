// A bench's item results (BenchRunner.cpp) combined into its results and written out: every seed
// of a graph pooled, speed-ups, the Pareto front, paired differences, and the header of bench.json.
#include <fstream>
#include <iostream>

#include "core/util/Error.h"
#include "eval/bench/BenchRunner.h"
#include "eval/report/OutputFolder.h"

namespace fovea::eval {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Every seed's run of one graph: times over the measured frames of all seeds; errors of one seed
// as FrameErrors gives them, of several the means over the seeds (combineSeedErrors).
BenchResult combineGraph(const BenchSpec& spec, const BenchGraph& g,
                         const std::vector<const json*>& runs) {
    BenchResult result;
    result.graph = g;
    result.output = runs.front()->at("output").get<std::string>();
    std::vector<double> frameMs;
    for (const json* run : runs)
        for (double ms : run->at("frame_ms")) frameMs.push_back(ms);
    result.frameMs = computeStats(frameMs);
    // The same graph every seed: the same passes in the same order.
    for (const json& p : runs.back()->at("passes")) {
        BenchPass pass;
        pass.name = p.at("name").get<std::string>();
        pass.type = p.at("type").get<std::string>();
        pass.status = p.at("status").get<std::string>();
        result.passes.push_back(pass);
    }
    for (size_t n = 0; n < result.passes.size(); ++n) {
        std::vector<double> ms;
        uint64_t executions = 0;
        for (const json* run : runs) {
            const json& p = run->at("passes").at(n);
            for (double v : p.at("ms")) ms.push_back(v);
            executions += p.at("executions").get<uint64_t>();
        }
        result.passes[n].gpuMs = computeStats(ms);
        result.passes[n].executions = executions;
    }
    const size_t tracks = runs.front()->at("tracks").size();
    for (size_t i = 0; i < tracks; ++i) {
        const json& first = runs.front()->at("tracks").at(i);
        BenchTrack track{first.at("label").get<std::string>(), {}, {}};
        if (runs.size() == 1) {
            track.meanErrors = metricsFromJson(first.at("mean"));
            track.errors = first.at("errors");
        } else {
            std::vector<ImageMetrics> means;
            std::vector<json> perSeed;
            for (const json* run : runs) {
                means.push_back(metricsFromJson(run->at("tracks").at(i).at("mean")));
                perSeed.push_back(run->at("tracks").at(i).at("errors"));
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

// bench.json's "reference": the rendered reference's info (its item's result) or the file, how it
// is read ("mode"), and its noise floor likewise.
json referenceInfo(const BenchSpec& spec, const std::vector<json>& results, const json& firstRun) {
    json reference, floor;
    for (const json& r : results) {
        if (r.at("kind") == "reference") reference = r.at("info");
        if (r.at("kind") == "noise_floor") floor = r.at("info");
    }
    if (!spec.reference.render) reference = {{"source", "file"}, {"path", spec.reference.file}};
    reference["mode"] = firstRun.at("reference_mode");
    if (!spec.noiseFloorRender && !spec.noiseFloor.empty())
        floor = {{"source", "file"}, {"path", spec.noiseFloor}};
    if (!floor.is_null()) reference["noise_floor"] = floor;
    return reference;
}

json benchHeader(const BenchSpec& spec, const std::vector<json>& results, const json& firstRun,
                 const std::optional<LayerRadii>& layers) {
    json header = {{"bench_version", 1},
                   {"fovea_version", FOVEA_VERSION},
                   {"bench", spec.file},
                   {"name", spec.name},
                   {"device", firstRun.at("device")},
                   {"scene", spec.scene},
                   {"camera", spec.camera.empty() ? json("still") : json(spec.camera)},
                   {"stereo", spec.stereo},
                   {"camera_model", spec.cameraModel.empty() ? "graph" : spec.cameraModel},
                   {"sun", spec.sun},
                   {"size", {spec.width, spec.height}},
                   {"frames", spec.frames},
                   {"warmup", spec.warmup},
                   {"seed", spec.seeds.front()},
                   {"reference", referenceInfo(spec, results, firstRun)}};
    if (!spec.env.empty()) header["env"] = firstRun.at("env");
    if (spec.seeds.size() > 1) header["seeds"] = spec.seeds;
    if (firstRun.contains("noise_floors") && !firstRun["noise_floors"].empty())
        header["noise_floor"] = firstRun["noise_floors"];
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
    return header;
}

}  // namespace

void collectBench(const BenchSpec& spec, const std::vector<json>& results,
                  const OutputFolder& folder, bool quiet) {
    const std::vector<BenchItem> plan = benchPlan(spec);
    const std::string key = benchKey(spec);
    if (results.size() != plan.size())
        throw InputError(spec.file, "",
                         "expected " + std::to_string(plan.size()) + " item results, got " +
                             std::to_string(results.size()));
    std::vector<std::vector<const json*>> runs(spec.graphs.size());
    for (size_t i = 0; i < plan.size(); ++i) {
        const json& r = results[i];
        if (r.value("item", "") != plan[i].name || r.value("bench_key", "") != key)
            throw InputError((folder.path() / benchItemResult(plan[i])).string(), "",
                             "this result is not item " + plan[i].name + " of " + spec.file +
                                 " (bench key " + key +
                                 "): it was written for another bench "
                                 "file or fovea version; rerun the item");
        if (plan[i].kind == BenchItem::Kind::Run) runs[plan[i].graph].push_back(&r);
    }
    std::vector<BenchResult> benchResults;
    for (size_t g = 0; g < spec.graphs.size(); ++g)
        benchResults.push_back(combineGraph(spec, spec.graphs[g], runs[g]));
    const double baseline = benchResults.front().frameMs.median;
    for (auto& r : benchResults)
        r.speedup = r.frameMs.median > 0 ? baseline / r.frameMs.median : 0.0;
    std::vector<double> ms, rmse;
    for (const auto& r : benchResults) {
        ms.push_back(r.frameMs.median);
        rmse.push_back(r.meanErrors.rmsePercent);
    }
    const std::vector<bool> pareto = paretoOptimal(ms, rmse);
    for (size_t i = 0; i < benchResults.size(); ++i) benchResults[i].pareto = pareto[i];
    if (spec.seeds.size() > 1)
        for (size_t i = 1; i < benchResults.size(); ++i)
            benchResults[i].difference = pairedDifference(
                benchResults[i].errors, benchResults[0].errors, benchResults[0].graph.label);
    const json& firstRun = *runs.front().front();
    const json header = benchHeader(spec, results, firstRun, benchLayerRadii(spec));

    const fs::path& dir = folder.path();
    const std::string deviceName = firstRun.at("device").at("name").get<std::string>();
    folder.writeText("bench.svg", benchPlotSvg(benchResults, spec.name + " — " + deviceName));
    writeBenchTables(folder, header, benchResults);
    if (!quiet) std::cerr << "fovea: wrote " << (dir / "bench.md").string() << "\n";
}

std::vector<json> readBenchResults(const BenchSpec& spec, const fs::path& dir) {
    std::vector<json> results;
    std::vector<std::string> missing;
    for (const BenchItem& item : benchPlan(spec)) {
        const fs::path file = dir / benchItemResult(item);
        std::ifstream in(file);
        if (!in) {
            missing.push_back(item.name);
            continue;
        }
        json j = json::parse(in, nullptr, false);
        if (j.is_discarded() || !j.is_object())
            throw InputError(file.string(), "",
                             "not a bench item result (invalid JSON); rerun the "
                             "item");
        results.push_back(std::move(j));
    }
    if (!missing.empty()) {
        std::string list;
        for (const auto& m : missing) list += (list.empty() ? "" : ", ") + m;
        throw InputError(dir.string(), "",
                         std::to_string(missing.size()) + " of " +
                             std::to_string(benchPlan(spec).size()) +
                             " bench items have no result yet: " + list);
    }
    return results;
}

}  // namespace fovea::eval
