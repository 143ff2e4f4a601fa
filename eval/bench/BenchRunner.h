// Running a bench file (docs/bench.md) as independent work items (docs/cluster.md): the rendered
// references first, then one item per graph and run seed. An item is a pure function of the bench
// file and its index, and its result is JSON; collectBench turns the results of every item into
// the same bench.json/.csv/.md/.svg whether the items ran in one process (`fovea bench`) or apart
// (`fovea bench --item K` on a cluster, then `fovea bench --collect`).
#pragma once
#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "eval/bench/Bench.h"

namespace fovea::gpu {
class Context;
}

namespace fovea::eval {

class OutputFolder;

struct BenchItem {
    enum class Kind { Reference, NoiseFloor, Run };
    Kind kind = Kind::Run;
    size_t graph = 0, seed = 0;  // Run: indices into BenchSpec::graphs and BenchSpec::seeds
    // "reference", "noise_floor" or "g<graph>_s<seed>": the item's folder under items/.
    std::string name;
};

// The bench's items in the order they may run: the references the runs measure against first.
std::vector<BenchItem> benchPlan(const BenchSpec& spec);
// `fovea bench --plan`: {"bench", "bench_key", "items": [{"index", "name", "kind" ("reference",
// "noise_floor", "run"), "needs": [indices of the items it reads], "result" (its result file,
// relative to the output folder), and for runs "graph" (label), "graph_index", "seed"}]}.
nlohmann::json benchPlanJson(const BenchSpec& spec);
// What ties an item's result to its bench: a hash of the parsed bench file and the fovea version,
// as hex. collectBench refuses results with another key.
std::string benchKey(const BenchSpec& spec);
// Where item `item`'s result is written under the output folder: items/<name>/result.json.
std::filesystem::path benchItemResult(const BenchItem& item);

// Loads every graph file with its --set and reads every file reference of the bench (InputError
// naming the bench file and pointer) before any device exists; returns the radii of the
// per-layer errors (the bench's "layers", else the first graph's FoveationMask facts).
std::optional<LayerRadii> checkBenchInputs(const BenchSpec& spec);
// Only the radii (no file checks): the bench's "layers", else the first FoveationMask's facts.
std::optional<LayerRadii> benchLayerRadii(const BenchSpec& spec);

// Runs one item, `dir` being the bench's output folder. A reference item renders into
// dir/reference or dir/reference_noise_floor (each taken as its own OutputFolder), reusing what is
// there while its key.json matches; a run item measures one graph with one seed against the
// references, and refuses (InputError) when a rendered one is missing or stale. Returns the result
// collectBench reads; writes nothing else.
nlohmann::json runBenchItem(const BenchSpec& spec, const BenchItem& item,
                            const std::filesystem::path& dir, gpu::Context& ctx, bool quiet);

// Writes bench.svg, bench.csv, bench.md and bench.json (last) into `folder` from the
// results of every item of benchPlan(spec), in plan order. Throws InputError when a result belongs
// to another bench (benchKey) or is not the item's.
void collectBench(const BenchSpec& spec, const std::vector<nlohmann::json>& results,
                  const OutputFolder& folder, bool quiet);
// Reads every item's result from dir/items (InputError listing the missing ones, naming a
// corrupt one), for `fovea bench --collect`.
std::vector<nlohmann::json> readBenchResults(const BenchSpec& spec,
                                             const std::filesystem::path& dir);

}  // namespace fovea::eval
