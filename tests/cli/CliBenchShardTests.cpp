// A bench run apart (docs/cluster.md, eval/bench/BenchRunner.h): `fovea bench --plan` lists the
// items (rendered references first), `--item K --out DIR` runs one, `--collect DIR` writes the
// tables. The collected bench must equal the one-process bench apart from what time decides
// (frame and pass milliseconds, speed-up, Pareto) and host fields, and collect must refuse
// missing items, an item run before the reference it reads, and results of another bench.
// Tiny sizes (lavapipe): 64x64, 3 frames, 4 spp references.
#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

json shardBench() {
    return {{"version", 1},
            {"name", "shards"},
            {"scene", "builtin:cornell"},
            {"size", {64, 64}},
            {"frames", 3},
            {"warmup", 1},
            {"seeds", {1, 2}},
            {"output", "acc.mean"},
            {"layers", {{"r0", 8}, {"r1", 20}}},
            {"reference", {{"render", {{"spp", 4}}}}},
            {"noise_floor", "render"},
            {"graphs",
             {{{"label", "spp 1"}, {"file", kDemoGraph.string()}, {"set", {"pt.spp=1"}}},
              {{"label", "spp 2"}, {"file", kDemoGraph.string()}, {"set", {"pt.spp=2"}}}}}};
}

// bench.json without what time and the host decide: frame and pass times, speed-ups, the Pareto
// flags (from the times), the device and whether a reference was reused; the output folder (in
// reference paths) reads DIR.
json withoutTimes(const fs::path& benchJson) {
    std::string text = readText(benchJson);
    const std::string dir = benchJson.parent_path().string() + "/";
    for (size_t at = text.find(dir); at != std::string::npos; at = text.find(dir, at))
        text.replace(at, dir.size(), "DIR/");
    json j = json::parse(text);
    j.erase("device");
    j.erase("finished");
    j["reference"].erase("cached");
    j["reference"]["noise_floor"].erase("cached");
    for (json& g : j["graphs"]) {
        for (const char* key : {"frame_ms", "speedup", "pareto"}) g.erase(key);
        for (json& p : g["passes"]) p.erase("gpu_ms");
    }
    return j;
}

// bench.csv without its time-derived columns.
std::string csvWithoutTimes(const std::string& csv) {
    std::vector<std::vector<std::string>> rows;
    std::istringstream in(csv);
    for (std::string line; std::getline(in, line);) {
        rows.emplace_back();
        std::istringstream cells(line);
        for (std::string cell; std::getline(cells, cell, ',');) rows.back().push_back(cell);
    }
    std::string out;
    for (const auto& row : rows) {
        for (size_t c = 0; c < row.size() && c < rows[0].size(); ++c) {
            const std::string& name = rows[0][c];
            if (name.find("_ms") != std::string::npos || name == "speedup" || name == "pareto")
                continue;
            out += row[c] + ",";
        }
        out += "\n";
    }
    return out;
}

}  // namespace

TEST(CliBenchShard, ItemsRunApartCollectToTheSameBench) {
    TempDir tmp;
    const fs::path file = tmp / "shards.bench.json";
    writeText(file, shardBench().dump(2));

    Result plan = cli({"bench", file.string(), "--plan"});
    ASSERT_EQ(plan.code, 0) << plan.describe();
    const json items = json::parse(plan.out).at("items");
    ASSERT_EQ(items.size(), 6u) << "2 references + 2 graphs x 2 seeds";
    EXPECT_EQ(items[0].at("kind"), "reference");
    EXPECT_EQ(items[1].at("kind"), "noise_floor");
    for (size_t i = 2; i < 6; ++i) {
        EXPECT_EQ(items[i].at("kind"), "run");
        EXPECT_EQ(items[i].at("needs"), json::array({0, 1})) << i;
        // Seed-major: both graphs with seed 1, then both with seed 2 (interleaved repeats).
        EXPECT_EQ(items[i].at("seed"), i < 4 ? 1 : 2);
        EXPECT_EQ(items[i].at("graph"), i % 2 == 0 ? "spp 1" : "spp 2");
    }

    const fs::path shards = tmp / "shards";
    // A run before its reference: refused, naming the item to run first.
    Result early =
        cli({"bench", file.string(), "--out", shards.string(), "--item", "2", "--quiet"});
    EXPECT_EQ(early.code, 2) << early.describe();
    EXPECT_TRUE(contains(early.err, "run item reference")) << early.err;
    // Runs in reverse order after the references: the order of runs does not matter.
    for (int k : {0, 1, 5, 4, 3, 2}) {
        Result r = cli({"bench", file.string(), "--out", shards.string(), "--item",
                        std::to_string(k), "--quiet"});
        ASSERT_EQ(r.code, 0) << k << ": " << r.describe();
        EXPECT_TRUE(fs::exists(shards / "items" / items[size_t(k)].at("name").get<std::string>() /
                               "result.json"))
            << k;
    }
    Result bad = cli({"bench", file.string(), "--out", shards.string(), "--item", "6"});
    EXPECT_EQ(bad.code, 2) << bad.describe();
    EXPECT_TRUE(contains(bad.err, "--item") && contains(bad.err, "0 to 5")) << bad.err;

    Result collect = cli({"bench", file.string(), "--collect", shards.string(), "--quiet"});
    ASSERT_EQ(collect.code, 0) << collect.describe();
    Result whole = cli({"bench", file.string(), "--out", (tmp / "whole").string(), "--quiet"});
    ASSERT_EQ(whole.code, 0) << whole.describe();

    const json a = withoutTimes(tmp / "whole" / "bench.json");
    const json b = withoutTimes(shards / "bench.json");
    EXPECT_EQ(json::parse(readText(shards / "bench.json")).at("finished"), true);
    EXPECT_TRUE(a.at("noise_floor").contains("reference")) << "measured once, with item g0_s0";
    EXPECT_EQ(a.at("graphs").size(), 2u);
    EXPECT_TRUE(a == b) << "collected and one-process benches differ:\n"
                        << json::diff(a, b).dump(1);
    EXPECT_EQ(csvWithoutTimes(readText(tmp / "whole" / "bench.csv")),
              csvWithoutTimes(readText(shards / "bench.csv")));
    EXPECT_NE(csvWithoutTimes(readText(shards / "bench.csv")).find("spp 2"), std::string::npos);

    // A missing item: collect lists it and writes nothing.
    fs::remove(shards / "bench.json");
    fs::rename(shards / "items" / "g1_s1", tmp / "g1_s1");
    Result missing = cli({"bench", file.string(), "--collect", shards.string(), "--quiet"});
    EXPECT_EQ(missing.code, 2) << missing.describe();
    EXPECT_TRUE(contains(missing.err, "1 of 6 bench items have no result yet: g1_s1"))
        << missing.err;
    EXPECT_FALSE(fs::exists(shards / "bench.json"));
    fs::rename(tmp / "g1_s1", shards / "items" / "g1_s1");

    // A result of another bench file (here: one more frame) is refused, not mixed in.
    json other = shardBench();
    other["frames"] = 4;
    writeText(file, other.dump(2));
    Result foreign = cli({"bench", file.string(), "--collect", shards.string(), "--quiet"});
    EXPECT_EQ(foreign.code, 2) << foreign.describe();
    EXPECT_TRUE(contains(foreign.err, "not item reference of") &&
                contains(foreign.err, "another bench file"))
        << foreign.err;
    EXPECT_FALSE(fs::exists(shards / "bench.json"));
}

TEST(CliBenchShard, ModesAreExclusive) {
    TempDir tmp;
    const fs::path file = tmp / "b.bench.json";
    writeText(file, shardBench().dump(2));
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"bench", file.string()},
          {"bench", file.string(), "--plan", "--out", (tmp / "o").string()},
          {"bench", file.string(), "--collect", tmp.path().string(), "--out",
           (tmp / "o").string()}}) {
        Result r = cli(args);
        EXPECT_EQ(r.code, 2) << r.describe();
        EXPECT_TRUE(contains(r.err, "one of --out DIR, --plan or --collect DIR")) << r.err;
    }
    Result notDir = cli({"bench", file.string(), "--collect", (tmp / "nothing").string()});
    EXPECT_EQ(notDir.code, 2) << notDir.describe();
    EXPECT_TRUE(contains(notDir.err, "--collect")) << notDir.err;
}
