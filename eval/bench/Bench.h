// `fovea bench`: the bench file (docs/bench.md), the measured results of each graph, and the
// files written from them (bench.json, bench.csv, bench.md, bench.svg).
#pragma once
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "eval/metrics/EccentricityBands.h"
#include "eval/metrics/ImageMetrics.h"
#include "eval/reference/ReferenceErrors.h"
#include "eval/report/Report.h"

namespace fovea::eval {

struct BenchGraph {
    std::string label, file;        // file resolved against the bench file's folder
    std::vector<std::string> sets;  // "pass.param=value", as --set
    std::string output;             // compared output; "" = the bench's, else the first float one
    std::string pointer;            // "/graphs/<i>"
};

struct BenchReference {
    std::string file;  // an EXR or a directory of per-frame EXRs; "" when rendered
    bool render = false;
    uint32_t spp = 1024;
    std::string graph;   // reference graph (default graphs/reference.json of the source tree)
    std::string output;  // its output used as the reference ("" = its first float output)
    std::vector<std::string> sets;
};

// Another reference every graph's output is also measured against (e.g. the pixel-centre
// reference of builtin:forest: the denoiser's own error, docs/benchmarks.md), with its noise floor.
struct BenchAgainst {
    std::string label, file;  // file: EXR, per-frame directory or printf pattern
    std::string noiseFloor;   // a second such reference with another seed; "" = none
    std::string pointer;      // "/also_against/<i>"
};

struct BenchSpec {
    std::string file, name;
    std::string scene, camera;  // camera: a camera path JSON, "" = the scene's still camera
    bool stereo = false;
    // `camera_model` (or fovea bench --camera-model): "perspective", "equirect"; "" = the graphs'
    std::string cameraModel;
    bool sun = false;  // `sun`: --sun for every graph and the reference (glTF files without lights)
    // `env`: --env, --env-intensity, --env-rotation for every graph and the reference.
    std::string env;
    float envIntensity = 1.0f, envRotation = 0.0f;
    uint32_t width = 0, height = 0, frames = 0, warmup = 1;
    // Run seeds: `seed` (one) or `seeds` (several: every graph runs once per seed, the errors are
    // means over the seeds with their standard error and paired differences, BenchSeeds.cpp).
    std::vector<uint64_t> seeds = {1};
    std::string output;
    BenchReference reference;
    // The reference's noise floor: a second reference with another seed (file, directory or
    // pattern) or, with noiseFloorRender, rendered like the reference with another seed.
    std::string noiseFloor;
    bool noiseFloorRender = false;
    std::vector<BenchAgainst> against;
    // Radii of the per-layer errors; unset: those of the first graph with a FoveationMask pass.
    std::optional<eval::LayerRadii> layers;
    // `flip`: ꟻLIP of every graph's output (and of the noise floor), docs/bench.md.
    FlipChoice flip;
    std::vector<BenchGraph> graphs;
};

// Throws InputError(file, JSON pointer, message) for a bad bench file.
BenchSpec parseBenchFile(const std::filesystem::path& file);

struct BenchPass {
    std::string name, type, status;
    Stats gpuMs;  // over the measured frames in which the pass ran (executed or bypassed)
    uint64_t executions = 0;  // measured frames in which it executed
};

// The errors of one output against one more reference (BenchSpec::against).
struct BenchTrack {
    std::string label;
    eval::ImageMetrics meanErrors;
    nlohmann::json errors;  // FrameErrors::json()
};

struct BenchResult {
    BenchGraph graph;
    std::string output;  // the output compared
    Stats frameMs;       // GPU frame time over the measured frames
    double speedup = 1;  // baseline (first graph) median frame ms / this graph's
    eval::ImageMetrics meanErrors;
    double temporalError = 0;
    nlohmann::json errors;            // FrameErrors::json()
    std::vector<BenchTrack> against;  // one per BenchSpec::against, in order
    bool pareto = false;              // Pareto-optimal in (frame ms median, mean RMSE %)
    std::vector<BenchPass> passes;
    // Several seeds only, every graph after the first: pairedDifference() against the first.
    nlohmann::json difference;
};

// Table text shared by bench.csv/bench.md and the seed tables (BenchText.cpp): a number in
// printf `format` ("nan", "inf" spelled out: a PSNR of identical images is infinite), and a
// Markdown table cell (a '|' would split the cell).
std::string benchNumber(double v, const char* format = "%.4g");
std::string benchMarkdown(const std::string& s);

// Several seeds (BenchSeeds.cpp, docs/bench.md "Several seeds").
// The errors of one output over the seeds, from each seed's FrameErrors::json(): "mean" (the mean
// over the seeds of each seed's mean; PSNR null when any is infinite), "standard_error" (same
// keys: sample standard deviation over the seeds / sqrt(seeds)), "temporal_error" (mean over the
// seeds) and "temporal_error_standard_error", "worst" (the worst frame of all seeds, with its
// "seed") and "seeds" (each seed's FrameErrors::json() with its "seed").
nlohmann::json combineSeedErrors(const std::vector<uint64_t>& seeds,
                                 const std::vector<nlohmann::json>& perSeed);
// The mean over the seeds of each figure (PSNR +inf when any is).
eval::ImageMetrics meanOverSeeds(const std::vector<eval::ImageMetrics>& perSeed);
// The paired difference of `graph` against `first` (both combineSeedErrors objects, same seeds):
// {"against": label, "figures": {name: {"seeds": [graph - first per seed], "mean",
// "standard_error", "significant": |mean| > 2 standard errors}}} for the figures of
// seedFigureNames() that both have.
nlohmann::json pairedDifference(const nlohmann::json& graph, const nlohmann::json& first,
                                const std::string& firstLabel);
// The figures compared over seeds, in table order: rmse, rmse_percent, the three bands
// (rmse_0_5deg, ...) and the three layers (rmse_percent_fovea, ...), as in bench.csv.
const std::vector<std::string>& seedFigureNames();
// One of those figures from an errors object's "mean" (FrameErrors::json() or
// combineSeedErrors): layers as RMSE % (100 RMSE, peak 1); NaN when it has none.
double benchFigure(const nlohmann::json& errors, const std::string& figure);
// bench.csv's columns for several seeds (appended after the others) and one graph's values.
std::string seedCsvHeader();
std::string seedCsvRow(const BenchResult& r);
// " ± <standard error of figure>" of a combineSeedErrors object; "" for one seed's errors.
std::string standardErrorSuffix(const nlohmann::json& errors, const std::string& figure,
                                const char* format);
// bench.md's sections for several seeds: each seed's own errors and the paired differences.
void seedTables(std::ostream& t, const std::vector<BenchResult>& results);

class OutputFolder;

// bench.csv, bench.md, then bench.json (everything, with "finished": true) last, each written
// checked and atomically through `folder`; `header` holds the run's description (device, scene,
// ...), with "noise_floor" ({"reference": FrameErrors::json() of the second reference against the
// first, "<label>": the same per also_against}) and "layers" ({"r0", "r1", "unit"}) when known.
void writeBenchTables(const OutputFolder& folder, const nlohmann::json& header,
                      const std::vector<BenchResult>& results);
// The run-time-vs-error plot as SVG text (BenchPlot.cpp).
std::string benchPlotSvg(const std::vector<BenchResult>& results, const std::string& title);

}  // namespace fovea::eval
