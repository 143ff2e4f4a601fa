// `fovea bench BENCH.json --out DIR`: runs every graph of a bench file on the same scene, camera
// path and size, measures GPU time per frame and per pass (medians over the frames after the
// warm-up) and the error of one output against a reference per frame, and writes tables and a
// run-time-vs-error plot (docs/bench.md).
#include <iostream>

#include "apps/fovea/CliChecks.h"
#include "apps/fovea/Commands.h"
#include "core/util/Error.h"
#include "core/vk/Context.h"
#include "eval/bench/Bench.h"
#include "eval/bench/BenchRunner.h"
#include "eval/report/OutputFolder.h"
#include "eval/run/GraphRunner.h"

namespace fovea::app {

namespace fs = std::filesystem;
using nlohmann::json;

void addBenchCommand(CLI::App& app, BenchOptions& o) {
    auto* cmd = app.add_subcommand(
        "bench", "run several graphs and compare run time against error (docs/bench.md)");
    cmd->add_option("bench", o.file, "bench file (JSON)")->required()->check(userPath());
    cmd->add_option("--out", o.out, "output directory for bench.json/.csv/.md/.svg")
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
    // Sharded (docs/cluster.md): the plan, one item of it, and the items' results combined.
    cmd->add_flag("--plan", o.plan,
                  "print the bench's independent work items as JSON (references first)");
    cmd->add_option("--item", o.item,
                    "run only item K of --plan into --out (its result in items/<name>/)");
    cmd->add_option("--collect", o.collect,
                    "write bench.json/.csv/.md/.svg of DIR from the results its items wrote")
        ->check(nonEmptyValue())
        ->check(userPath());
}

int benchCommand(const BenchOptions& o) {
    const int modes = int(o.plan) + int(!o.collect.empty()) + int(!o.out.empty());
    if (modes != 1) throw InputError("--out", "", "give one of --out DIR, --plan or --collect DIR");
    BenchSpec spec = parseBenchFile(o.file);
    if (!o.cameraModel.empty()) {
        spec.cameraModel = o.cameraModel;
        if (o.cameraModel == "equirect" && spec.width != 2 * spec.height)
            throw InputError("--camera-model", "",
                             "an equirect camera needs a 2:1 image; " + spec.file + ": /size is " +
                                 std::to_string(spec.width) + "x" + std::to_string(spec.height));
    }
    if (o.plan) {
        checkBenchInputs(spec);
        std::cout << benchPlanJson(spec).dump(2) << "\n";
        return kExitOk;
    }
    if (!o.collect.empty()) {
        // The folder the items wrote into: never empty, so taken as with --overwrite (only an
        // old bench.json goes first).
        const fs::path dir = o.collect;
        if (!fs::is_directory(dir))
            throw InputError("--collect", "", "'" + dir.string() + "' is not a directory");
        const std::vector<json> results = readBenchResults(spec, dir);
        const OutputFolder folder(dir, "--collect", true, "bench.json");
        collectBench(spec, results, folder, o.quiet);
        return kExitOk;
    }
    const fs::path dir = o.out;
    const std::vector<BenchItem> plan = benchPlan(spec);
    if (o.item && *o.item >= plan.size())
        throw InputError("--item", "",
                         std::to_string(*o.item) + " is not an item of " + spec.file + " (it has " +
                             std::to_string(plan.size()) + ", 0 to " +
                             std::to_string(plan.size() - 1) + "; see --plan)");
    if (!o.item) checkOutputDir(dir, "--out", o.overwrite);
    // Every graph file, --set and file reference is checked before the device exists.
    checkBenchInputs(spec);
    if (o.item) {
        // One item of a sharded bench: its own folder (locked, result.json written last), the
        // bench folder shared with the other items.
        const BenchItem& item = plan[*o.item];
        const OutputFolder folder(dir / benchItemResult(item).parent_path(), "--item", true,
                                  "result.json");
        std::optional<gpu::Context> device;
        gpu::Context& ctx = openDevice(device, o.device, o.validation, o.quiet);
        const json result = runBenchItem(spec, item, dir, ctx, o.quiet);
        folder.writeText("result.json", result.dump(1) + "\n");
        return kExitOk;
    }
    // Taken like `fovea run`'s folder (OutputFolder.h): locked, emptiness re-checked under the
    // lock, every file written checked under a temporary name, bench.json last with "finished".
    const OutputFolder folder(dir, "--out", o.overwrite, "bench.json");
    std::optional<gpu::Context> device;
    gpu::Context& ctx = openDevice(device, o.device, o.validation, o.quiet);
    // The items in plan order, in this process: the same results --item and --collect combine.
    std::vector<json> results;
    for (const BenchItem& item : plan)
        results.push_back(runBenchItem(spec, item, dir, ctx, o.quiet));
    collectBench(spec, results, folder, o.quiet);
    return kExitOk;
}

}  // namespace fovea::app
