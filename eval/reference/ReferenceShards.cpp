// Rendering one shard of a reference (ReferenceShards.h); merging them is ReferenceMerge.cpp.
#include "eval/reference/ReferenceShards.h"

#include <chrono>
#include <fstream>
#include <iostream>
#include <regex>

#include "core/util/Error.h"
#include "core/util/Hash.h"
#include "core/vk/Context.h"
#include "eval/reference/ReferenceErrors.h"
#include "eval/reference/ReferenceRender.h"
#include "eval/report/OutputFolder.h"
#include "eval/run/Progress.h"

namespace fovea::eval {

namespace fs = std::filesystem;
using nlohmann::json;

Shard parseShard(const std::string& text, const std::string& flag) {
    static const std::regex kPattern(R"((\d{1,5})/(\d{1,5}))");
    std::smatch m;
    if (!std::regex_match(text, m, kPattern))
        throw InputError(flag, "", "expected I/N (shard I of N, 0 <= I < N), got '" + text + "'");
    const uint32_t index = uint32_t(std::stoul(m[1])), count = uint32_t(std::stoul(m[2]));
    if (count < 1 || count > 65536 || index >= count)
        throw InputError(
            flag, "",
            "expected I/N with 0 <= I < N <= 65536 (shards count from 0), got '" + text + "'");
    return {index, count};
}

FrameRange shardRange(const Shard& shard, uint32_t total) {
    // 64-bit products: total * index stays exact for any uint32 total and N <= 65536.
    return {uint32_t(uint64_t(total) * shard.index / shard.count),
            uint32_t(uint64_t(total) * (shard.index + 1) / shard.count)};
}

FrameRange parseFrameRange(const std::string& text, const std::string& flag) {
    static const std::regex kPattern(R"((\d{1,9}):(\d{1,9}))");
    std::smatch m;
    if (!std::regex_match(text, m, kPattern))
        throw InputError(flag, "", "expected FIRST:LAST (camera path frames), got '" + text + "'");
    const uint32_t first = uint32_t(std::stoul(m[1])), last = uint32_t(std::stoul(m[2]));
    if (first > last) throw InputError(flag, "", "FIRST > LAST in '" + text + "'");
    return {first, last + 1};
}

json shardKey(const ShardRequest& r, const std::vector<std::string>& sets, const json& scene) {
    // The graph as parsed JSON: formatting does not matter, a changed parameter does.
    const json graph = json::parse(std::ifstream(r.graphFile), nullptr, false);
    json key = {{"fovea_version", FOVEA_VERSION},
                {"kind", r.kind},
                {"shards", r.shard.count},
                {"graph", r.graphFile},
                {"graph_hash", fnv1aHex(graph.dump())},
                {"set", sets},
                {"scene", scene},
                {"size", {r.width, r.height}},
                {"seed", r.seed},
                {"spp", r.spp},
                {"samples_per_frame", referenceSamplesPerFrame(r.desc, r.graphFile)},
                {"output", r.output}};
    if (r.kind == "samples") {
        key["frames"] = referenceFrames(r.spp, key["samples_per_frame"].get<uint32_t>());
        key["path_frame"] = r.pathFrame ? json(*r.pathFrame) : json(nullptr);
    } else {
        key["path_frames"] = {r.pathFrames.begin, r.pathFrames.end - 1};
    }
    return key;
}

FrameRange shardFrames(const ShardRequest& r) {
    const bool samples = r.kind == "samples";
    const uint32_t total =
        samples ? referenceFrames(r.spp, referenceSamplesPerFrame(r.desc, r.graphFile))
                : r.pathFrames.size();
    const FrameRange range = shardRange(r.shard, total);
    if (range.size() == 0)
        throw InputError(samples ? "--shard" : "--frames-of", "",
                         "shard " + std::to_string(r.shard.index) + " of " +
                             std::to_string(r.shard.count) +
                             " has no frames: " + std::to_string(total) +
                             (samples ? " frames (of the spp)" : " path frames") +
                             " cannot be split " + std::to_string(r.shard.count) +
                             " ways; use at most " + std::to_string(total) + " shards");
    return range;
}

namespace {

std::string frameFile(uint32_t f) {
    char name[32];
    std::snprintf(name, sizeof name, "frame%04u.exr", f);
    return name;
}

}  // namespace

void renderReferenceShard(gpu::Context& ctx, RunScene& scene, const ShardRequest& r,
                          const OutputFolder& folder, bool quiet) {
    const auto start = std::chrono::steady_clock::now();
    const uint32_t perFrame = referenceSamplesPerFrame(r.desc, r.graphFile);
    json info = {{"shard_version", 1},  {"kind", r.kind}, {"shard", r.shard.index},
                 {"of", r.shard.count}, {"key", r.key},   {"device", ctx.deviceName()}};
    if (r.kind == "samples") {
        const FrameRange frames = shardFrames(r);
        // The single run's frames [begin, end), with their indices: their sample streams.
        GraphRunner runner(ctx, scene, r.desc,
                           {r.width, r.height, r.seed, true, r.pathFrame, frames.begin});
        const std::string output = selectComparedOutput(runner, r.output, "--graph");
        Progress progress(frames.size(), perFrame, quiet);
        for (uint32_t f = 0; f < frames.size(); ++f) {
            runner.runFrame();
            progress.update(f + 1);
        }
        progress.finish();
        // Accumulate's output is the mean of the shard's frames; the sum is what merges.
        image::ImageRGBA sum = runner.download(output);
        const uint64_t samples = uint64_t(frames.size()) * perFrame;
        for (float& v : sum.pixels) v = float(double(v) * double(samples));
        folder.write(kShardSumFile, [&](const fs::path& path) { image::writeExr(path, sum); });
        info.update(
            {{"frames", {frames.begin, frames.end}}, {"samples", samples}, {"output", output}});
    } else {
        const FrameRange block = shardFrames(r);
        json list = json::array();
        for (uint32_t i = block.begin; i < block.end; ++i) {
            const uint32_t f = r.pathFrames.begin + i;
            if (!quiet) std::cerr << "fovea: reference of path frame " << f << "\n";
            const image::ImageRGBA img = renderReferenceImage(
                ctx, scene, r.desc, r.graphFile, r.spp,
                {r.width, r.height, r.seed, true, uint64_t(f)}, r.output, "--graph", quiet);
            folder.write(frameFile(f), [&](const fs::path& path) { image::writeExr(path, img); });
            list.push_back(f);
        }
        // Per frame: the whole frames the spp round up to, as renderReferenceImage renders them.
        info.update({{"frames", list}, {"samples", referenceFrames(r.spp, perFrame) * perFrame}});
    }
    checkValidation(ctx);
    info["render_ms"] =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    folder.writeText(kShardFile, info.dump(2) + "\n");
}

}  // namespace fovea::eval
