// Sharded references (docs/cluster.md): one converged reference split by samples
// (`fovea reference --shard I/N`) or the per-frame references of a camera path split by frames
// (`fovea reference --path-frames A:B --frames-of I/N`), and `fovea merge`, which combines the
// shards into the files a single run writes.
//
// Each shard is a pure function of its inputs. A sample shard renders a contiguous block of the
// single run's frames, with their frame indices: the path tracer's sample streams are a hash of
// (seed, pixel, frame index, sample), so no two shards share a stream and the N shards together
// trace exactly the samples of the single run. A frame shard renders whole frames, each exactly
// as the single run does. Every shard writes `shard.json` last (its done marker) with a key of
// everything its image depends on; merge refuses shards whose keys differ.
#pragma once
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "eval/run/GraphRunner.h"

namespace fovea::eval {

class OutputFolder;

// Shard `index` of `count`, 0-based ("I/N" with 0 <= I < N: Slurm's array task ids).
struct Shard {
    uint32_t index = 0, count = 1;
};
// Parses "I/N" (N in 1..65536); errors name `flag`.
Shard parseShard(const std::string& text, const std::string& flag);

// Frames [begin, end).
struct FrameRange {
    uint32_t begin = 0, end = 0;
    uint32_t size() const { return end - begin; }
};
// Shard I of N of `total`: [floor(I total / N), floor((I+1) total / N)). The ranges of shards
// 0..N-1 are disjoint, in order and cover [0, total); a shard is empty when N > total.
FrameRange shardRange(const Shard& shard, uint32_t total);
// "A:B" (inclusive, A <= B) -> [A, B + 1); errors name `flag`.
FrameRange parseFrameRange(const std::string& text, const std::string& flag);

inline constexpr const char* kShardFile = "shard.json";
inline constexpr const char* kShardSumFile = "sum.exr";

// What one shard renders, and everything its pixels depend on (the key merge compares).
struct ShardRequest {
    std::string kind;  // "samples" or "frames"
    Shard shard;
    std::string graphFile;
    graph::GraphDesc desc;  // loaded, --set applied
    std::string output;     // "" = the first float output
    uint32_t width = 0, height = 0;
    uint64_t seed = 0;
    uint32_t spp = 0;
    std::optional<uint64_t> pathFrame;  // samples: the camera held at this path frame
    FrameRange pathFrames;              // frames: the path frames of the whole reference
    nlohmann::json key;                 // shardKey(): the inputs as JSON
};
// The key of a request: fovea version, kind, shard count, graph file with a hash of its parsed
// JSON, --set, `scene` (the scene options as the caller describes them), size, seed, spp and
// samples per frame, output, path frame(s).
nlohmann::json shardKey(const ShardRequest& request, const std::vector<std::string>& sets,
                        const nlohmann::json& scene);

// The frames shard r.shard renders: a block of the single run's frames (samples) or an index
// block of r.pathFrames (frames). InputError naming --shard or --frames-of when it is empty.
FrameRange shardFrames(const ShardRequest& request);

// Renders the shard on `ctx` into `folder`: a sample shard writes sum.exr (the sum over its
// samples of the output, RGBA float) and a frame shard frameNNNN.exr per frame (the converged
// reference of that path frame); shard.json last: {"shard_version", "kind", "shard", "of",
// "key", "frames" ([begin, end) of the run's frames, or the path frames), "samples" (per pixel),
// "output", "device", "render_ms"}. Throws InputError (naming `--shard`/`--frames-of`) for an
// empty shard.
void renderReferenceShard(gpu::Context& ctx, RunScene& scene, const ShardRequest& request,
                          const OutputFolder& folder, bool quiet);

// `fovea merge DIR... --out OUT`: the shards' images combined into the files one `fovea
// reference` writes: for sample shards `<output>.frameNNNN.exr` and `.png` (NNNN the single
// run's last frame; no suffix for a 1-frame run), the sample-weighted mean of the sums; for frame
// shards every frameNNNN.exr; and report.json ("merged_from", "finished": true) last.
// InputError (exit 2) naming the shard for another key, a missing or duplicate shard (listing
// them), a folder without shard.json; RuntimeError (exit 1) naming the shard for a NaN or
// infinite sum.
void mergeReferenceShards(const std::vector<std::filesystem::path>& shards, const OutputFolder& out,
                          bool quiet);

}  // namespace fovea::eval
