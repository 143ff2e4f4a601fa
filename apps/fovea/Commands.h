// Subcommands of the `fovea` executable. Each returns the process exit code:
// 0 ok, 1 runtime failure, 2 bad input or usage.
#pragma once
#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "apps/fovea/EvalNames.h"
#include "core/graph/GraphDesc.h"
#include "eval/run/GraphLoading.h"
#include "eval/run/SceneSetup.h"

namespace fovea::app {

constexpr int kExitOk = 0;
constexpr int kExitRuntime = 1;
constexpr int kExitInput = 2;

// Adds the scene options (eval::SceneOptions) to a subcommand (SceneOptionsCli.cpp).
void addSceneOptions(CLI::App& cmd, SceneOptions& o);

struct RunOptions {
    GraphOptions graph;
    SceneOptions scene;
    int frames = 0;     // 0 = graph default (or 1)
    int64_t seed = -1;  // -1 = graph default (or 0)
    std::string out;
    std::string saveFrames = "last";
    std::string device;
    bool validation = false;
    bool overwrite = false;
    bool quiet = false;
    // `fovea reference`: a progress bar with an ETA counting samples per pixel instead of frames.
    uint32_t samplesPerFrame = 0;  // 0 = plain frame counter
    // --reference: an EXR (every frame) or a directory of per-frame EXRs (ReferenceErrors.h);
    // errors of `referenceOutput` (default: the first float output) go into report.json.
    std::string reference, referenceOutput;
    // --reference-noise: a second reference with another seed; report.json gets the noise floor
    // (its errors against --reference) next to the errors.
    std::string referenceNoise;
    // ꟻLIP of the compared output (ReferenceErrors.h FlipChoice): --no-flip, --flip-mode
    // auto|ldr|hdr, --flip-ppd NUMBER|camera ("" = the default observer).
    bool noFlip = false;
    std::string flipMode = "auto", flipPpd;
    // `fovea reference --path-frame F`: every frame uses camera-path frame F (a converged
    // reference of one frame of a moving camera path).
    std::optional<uint64_t> fixedCameraFrame;
    bool profileDispatches = false;  // --profile-dispatches: per-dispatch GPU timestamps
};

void addRunCommand(CLI::App& app, RunOptions& options);
int runCommand(const RunOptions& options);

// `fovea reference`: a converged image of a scene (graphs/reference.json by default).
struct ReferenceOptions {
    RunOptions run;
    int spp = 1024;
    int64_t pathFrame = -1;     // --path-frame; -1 = none
    bool pixelCentres = false;  // --pixel-centres: graphs/reference_pixel_centres.json
    // Sharded references (eval/reference/ReferenceShards.h, docs/cluster.md): --shard I/N (by
    // samples), --path-frames FIRST:LAST (per-frame references of a camera path) with
    // --frames-of I/N (by frames); "" = not given.
    std::string shard, pathFrames, framesOf;
};
void addReferenceCommand(CLI::App& app, ReferenceOptions& options);
int referenceCommand(ReferenceOptions options);

// `fovea merge`: reference shards into the files of one `fovea reference` (docs/cluster.md).
struct MergeOptions {
    std::vector<std::string> shards;
    std::string out;
    bool overwrite = false, quiet = false;
};
void addMergeCommand(CLI::App& app, MergeOptions& options);
int mergeCommand(const MergeOptions& options);

// `fovea bench`: run time against error of several graphs (docs/bench.md).
struct BenchOptions {
    std::string file, out, device;
    std::string cameraModel;  // --camera-model: overrides the bench file's camera_model
    bool validation = false, overwrite = false, quiet = false;
    // Sharded benches (docs/cluster.md): --plan prints the items, --item K runs one into --out,
    // --collect DIR writes the tables from their results.
    bool plan = false;
    std::optional<size_t> item;
    std::string collect;
};
void addBenchCommand(CLI::App& app, BenchOptions& options);
int benchCommand(const BenchOptions& options);

// The rule of run and bench: `dir` must be a directory (or absent) and empty unless overwrite.
void checkOutputDir(const std::filesystem::path& dir, const std::string& option, bool overwrite);

struct ValidateOptions {
    GraphOptions graph;
    SceneOptions scene;
    bool dump = false;
    bool json = false;
};
void addValidateCommand(CLI::App& app, ValidateOptions& options);
int validateCommand(const ValidateOptions& options);

struct PassesOptions {
    bool json = false;
    bool markdown = false;     // the generated doc tables of each type
    std::string updateDocs;    // rewrite the generated tables of DIR/<Type>.md
    std::string checkDocs;     // exit 1 when a page in DIR is stale or missing
    bool pluginsOnly = false;  // only the types plugins registered (a plugin's own docs)
    std::string type;
};
void addPassesCommand(CLI::App& app, PassesOptions& options);
int passesCommand(const PassesOptions& options);

// `fovea compare`: error metrics of an image against a reference (docs/metrics.md).
struct CompareOptions {
    std::string test, reference;
    bool json = false;
    double peak = 1.0;
    double epsilon = 1e-2;
    // ꟻLIP (eval/flip/Flip.h, docs/metrics.md "ꟻLIP").
    bool flipOnly = false;          // --flip: only the ꟻLIP figures
    bool noFlip = false;            // --no-flip
    std::string flipMode = "auto";  // auto (by the reference's file type) | ldr | hdr
    double ppd = 0;                 // 0: ꟻLIP's default observer (67.02 ppd)
    std::optional<double> startExposure, stopExposure;
    std::string flipMap;     // the error map image (.exr or .png)
    bool overwrite = false;  // --flip-map may replace an existing file
};
void addCompareCommand(CLI::App& app, CompareOptions& options);
int compareCommand(const CompareOptions& options);

// `fovea inspect`: the ImGui graph inspector in a window (docs/inspector.md).
struct InspectOptions {
    GraphOptions graph;
    SceneOptions scene;
    int frames = 0;  // 0 = until the window is closed
    int64_t seed = -1;
    std::string screenshot, script, device, window = "960x600", reference;
    bool validation = false, quiet = false, overwrite = false;
};
void addInspectCommand(CLI::App& app, InspectOptions& options);
int inspectCommand(const InspectOptions& options);

// `fovea gain`: P1's theoretical foveation gain of a display next to the samples fovea's
// foveated layouts trace on it (docs/gain-model.md). Values are kept as text and parsed by the
// command, so every error names its option; "" = not given.
struct GainOptions {
    std::string preset, fov, shape, cpd, resolution, gaze;
    std::string measure = "flat", density = "linear";
    std::string peresR0, peresR1, peresP = "0.5";
    std::string vpReduction = "0.61", vpFoveaFraction = "0.24", fvBudget = "100000";
    bool json = false;
};
void addGainCommand(CLI::App& app, GainOptions& options);
int gainCommand(const GainOptions& options);

// `fovea devices`: the Vulkan devices --device chooses from, and the one it picks by default
// (scripts/gpu-check.sh records this first).
struct DevicesOptions {
    bool json = false;
};
void addDevicesCommand(CLI::App& app, DevicesOptions& options);
int devicesCommand(const DevicesOptions& options);

}  // namespace fovea::app
