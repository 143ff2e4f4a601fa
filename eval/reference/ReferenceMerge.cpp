// `fovea merge`: reference shards (ReferenceShards.h) combined into the files of a single run.
#include <cmath>
#include <fstream>
#include <iostream>
#include <map>

#include "core/util/Error.h"
#include "eval/reference/ReferenceShards.h"
#include "eval/report/OutputFolder.h"

namespace fovea::eval {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct ShardFolder {
    fs::path dir;
    json info;  // shard.json
};

ShardFolder readShard(const fs::path& dir) {
    const fs::path file = dir / kShardFile;
    std::ifstream in(file);
    if (!in)
        throw InputError(file.string(), "",
                         "not a finished reference shard (no " + std::string(kShardFile) +
                             "): the shard failed or is still running; rerun it");
    json info = json::parse(in, nullptr, false);
    if (info.is_discarded() || !info.is_object() || !info.contains("key") ||
        !info["key"].is_object() || !info.contains("shard") || !info.contains("of"))
        throw InputError(file.string(), "", "not a reference shard's shard.json");
    return {dir, std::move(info)};
}

std::string joined(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
    return out;
}

// Every shard has the first one's key, and indices 0..N-1 appear exactly once.
void checkShardSet(const std::vector<ShardFolder>& shards) {
    const json& key = shards.front().info["key"];
    for (const ShardFolder& s : shards) {
        const json& other = s.info["key"];
        for (const auto& [field, value] : key.items())
            if (!other.contains(field) || other[field] != value)
                throw InputError((s.dir / kShardFile).string(), "/key/" + field,
                                 "differs from " + (shards.front().dir / kShardFile).string() +
                                     " (" + (other.contains(field) ? other[field].dump() : "none") +
                                     " vs " + value.dump() +
                                     "): shards of different references cannot be merged");
        if (other.size() != key.size())
            throw InputError((s.dir / kShardFile).string(), "/key",
                             "has other fields than " + (shards.front().dir / kShardFile).string());
    }
    const uint32_t count = key.at("shards").get<uint32_t>();
    std::map<uint32_t, std::vector<std::string>> byIndex;
    for (const ShardFolder& s : shards) {
        const uint32_t index = s.info["shard"].get<uint32_t>();
        if (index >= count)
            throw InputError((s.dir / kShardFile).string(), "/shard",
                             "shard " + std::to_string(index) + " of " + std::to_string(count) +
                                 " is out of range");
        byIndex[index].push_back(s.dir.string());
    }
    std::vector<std::string> missing, duplicate;
    for (uint32_t i = 0; i < count; ++i) {
        if (!byIndex.count(i)) missing.push_back(std::to_string(i));
        if (byIndex.count(i) && byIndex[i].size() > 1)
            duplicate.push_back(std::to_string(i) + " (" + joined(byIndex[i]) + ")");
    }
    if (!missing.empty() || !duplicate.empty())
        throw InputError(
            "fovea merge", "",
            "the shards do not make one reference of " + std::to_string(count) +
                " shards:" + (missing.empty() ? "" : " missing shard(s) " + joined(missing) + ";") +
                (duplicate.empty() ? "" : " duplicate shard(s) " + joined(duplicate) + ";"));
}

// The sample-weighted mean of the shards' sums, in double.
image::ImageRGBA mergeSamples(const std::vector<ShardFolder>& shards, json& from) {
    const json& key = shards.front().info["key"];
    const uint32_t width = key["size"][0], height = key["size"][1];
    std::vector<double> total(size_t(width) * height * 4, 0.0);
    uint64_t samples = 0;
    for (const ShardFolder& s : shards) {
        const fs::path file = s.dir / kShardSumFile;
        const image::ImageRGBA sum = image::readImage(file);
        if (sum.width != width || sum.height != height)
            throw InputError(file.string(), "",
                             "is " + std::to_string(sum.width) + "x" + std::to_string(sum.height) +
                                 ", the shard's key says " + std::to_string(width) + "x" +
                                 std::to_string(height));
        for (size_t i = 0; i < total.size(); ++i) {
            if (!std::isfinite(sum.pixels[i]))
                throw RuntimeError(file.string() + ": pixel (" + std::to_string(i / 4 % width) +
                                   ", " + std::to_string(i / 4 / width) + ") is " +
                                   (std::isnan(sum.pixels[i]) ? "NaN" : "infinite") +
                                   ": this shard's render is poisoned; rerun it (the others "
                                   "are kept)");
            total[i] += double(sum.pixels[i]);
        }
        samples += s.info.at("samples").get<uint64_t>();
        from.push_back({{"dir", s.dir.string()},
                        {"shard", s.info["shard"]},
                        {"frames", s.info["frames"]},
                        {"samples", s.info["samples"]},
                        {"device", s.info.value("device", "")},
                        {"render_ms", s.info.value("render_ms", 0.0)}});
    }
    image::ImageRGBA mean{width, height, std::vector<float>(total.size())};
    // samples >= 1: every shard renders at least one frame of at least one sample.
    for (size_t i = 0; i < total.size(); ++i) mean.pixels[i] = float(total[i] / double(samples));
    return mean;
}

}  // namespace

void mergeReferenceShards(const std::vector<fs::path>& dirs, const OutputFolder& out, bool quiet) {
    if (dirs.empty()) throw InputError("fovea merge", "", "no shard folders given");
    std::vector<ShardFolder> shards;
    for (const fs::path& dir : dirs) shards.push_back(readShard(dir));
    checkShardSet(shards);
    const json& key = shards.front().info["key"];
    json report = {
        {"fovea_version", FOVEA_VERSION}, {"merged", true},          {"key", key},
        {"graph", key["graph"]},          {"size", key["size"]},     {"seed", key["seed"]},
        {"merged_from", json::array()},   {"outputs", json::array()}};
    if (key.at("kind") == "samples") {
        const image::ImageRGBA mean = mergeSamples(shards, report["merged_from"]);
        // The names of a single `fovea reference` run's files of its last frame.
        const uint32_t frames = key.at("frames").get<uint32_t>();
        std::string base = shards.front().info.at("output").get<std::string>();
        if (frames > 1) {
            char suffix[32];
            std::snprintf(suffix, sizeof suffix, ".frame%04u", frames - 1);
            base += suffix;
        }
        out.write(base + ".exr", [&](const fs::path& path) { image::writeExr(path, mean); });
        out.write(base + ".png", [&](const fs::path& path) {
            image::writePng(path, mean, image::PngEncoding::Srgb);
        });
        report["frames_run"] = frames;
        report["outputs"] = {base + ".exr", base + ".png"};
    } else {
        for (const ShardFolder& s : shards) {
            for (const json& f : s.info.at("frames")) {
                char name[32];
                std::snprintf(name, sizeof name, "frame%04u.exr", f.get<uint32_t>());
                const fs::path from = s.dir / name;
                if (!fs::exists(from))
                    throw InputError(from.string(), "", "listed in shard.json but missing");
                out.write(name, [&](const fs::path& path) {
                    fs::copy_file(from, path, fs::copy_options::overwrite_existing);
                });
                report["outputs"].push_back(name);
            }
            report["merged_from"].push_back({{"dir", s.dir.string()},
                                             {"shard", s.info["shard"]},
                                             {"frames", s.info["frames"]},
                                             {"device", s.info.value("device", "")},
                                             {"render_ms", s.info.value("render_ms", 0.0)}});
        }
    }
    report["finished"] = true;
    out.writeText("report.json", report.dump(2) + "\n");
    if (!quiet)
        std::cerr << "fovea: merged " << shards.size() << " shards into " << out.path().string()
                  << "\n";
}

}  // namespace fovea::eval
