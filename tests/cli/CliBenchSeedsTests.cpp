// `fovea bench` with the key `seeds` (docs/bench.md "Several seeds", eval/bench/BenchSeeds.cpp):
// every graph runs once per seed; the errors are the means over the seeds of each seed's mean,
// with their standard error and each seed's own errors, and every graph after the first gets its
// paired difference against the first (per seed graph - first, mean ± s.e., flagged beyond
// 2 s.e.). Why: on the forest 512² bench one seed's fovea band said the opposite of the mean over
// six seeds (issue 11). One seed (`seed`, or `seeds` with one entry) writes what it always did.
// Tiny sizes (lavapipe): 64x64, 3 frames, a 4 spp reference.
#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

json seedsBench() {
    return {{"version", 1},
            {"name", "seeds"},
            {"scene", "builtin:cornell"},
            {"size", {64, 64}},
            {"frames", 3},
            {"warmup", 1},
            {"seeds", {1, 2}},
            {"output", "acc.mean"},
            {"layers", {{"r0", 8}, {"r1", 20}}},
            {"reference", {{"render", {{"spp", 4}}}}},
            // The second graph changes the output (2 spp); the third is the first again.
            {"graphs",
             {{{"label", "spp 1"}, {"file", kDemoGraph.string()}, {"set", {"pt.spp=1"}}},
              {{"label", "spp 2"}, {"file", kDemoGraph.string()}, {"set", {"pt.spp=2"}}},
              {{"label", "spp 1 again"}, {"file", kDemoGraph.string()}, {"set", {"pt.spp=1"}}}}}};
}

Result benchSeeds(const TempDir& tmp, const json& spec, const std::string& out) {
    const fs::path file = tmp / (out + ".bench.json");
    writeText(file, spec.dump(2));
    return cli({"bench", file.string(), "--out", (tmp / out).string(), "--quiet"});
}

// The figures compared over seeds, read from an errors "mean" object: RMSE, the three
// eccentricity bands' RMSE and the three layers' RMSE.
std::vector<double> figures(const json& mean) {
    std::vector<double> out = {mean.at("rmse").get<double>()};
    for (const char* list : {"bands", "layers"}) {
        EXPECT_EQ(mean.at(list).size(), 3u) << list;
        for (const json& b : mean.at(list)) out.push_back(b.at("rmse").get<double>());
    }
    return out;
}

const char* const kFigureNames[] = {"rmse",
                                    "rmse_0_5deg",
                                    "rmse_5_20deg",
                                    "rmse_20deg_plus",
                                    "rmse_percent_fovea",
                                    "rmse_percent_middle",
                                    "rmse_percent_outer"};
// Layers are reported in RMSE % (= 100 RMSE, peak 1) like bench.csv's layer columns.
double scaleOf(size_t figure) {
    return figure >= 4 ? 100.0 : 1.0;
}

}  // namespace

TEST(CliBenchSeeds, MeansPerSeedErrorsAndPairedDifferences) {
    TempDir tmp;
    Result r = benchSeeds(tmp, seedsBench(), "out");
    ASSERT_EQ(r.code, 0) << r.describe();
    const json j = json::parse(readText(tmp / "out" / "bench.json"));
    EXPECT_EQ(j.at("seeds"), json::array({1, 2}));
    EXPECT_EQ(j.at("seed"), 1);
    EXPECT_EQ(j.at("reference").at("seed"), 3) << "max(seeds) + 1: no run seed";
    ASSERT_EQ(j.at("graphs").size(), 3u);

    std::vector<std::vector<std::vector<double>>> perSeed;  // [graph][seed][figure]
    for (const json& g : j["graphs"]) {
        const json& e = g.at("errors");
        ASSERT_EQ(e.at("seeds").size(), 2u) << g["label"];
        perSeed.emplace_back();
        std::vector<double> temporal;
        for (size_t s = 0; s < 2; ++s) {
            const json& one = e["seeds"][s];
            EXPECT_EQ(one.at("seed"), s + 1);
            EXPECT_EQ(one.at("frames").size(), 2u) << "the measured frames of that seed";
            perSeed.back().push_back(figures(one.at("mean")));
            temporal.push_back(one.at("temporal_error").get<double>());
        }
        const auto& a = perSeed.back()[0];
        const auto& b = perSeed.back()[1];
        EXPECT_NE(a[0], b[0])
            << "seeds 1 and 2 gave the same error: the seed did not reach the run";
        // The mean is the mean of the seeds' means, the standard error of two values |a - b| / 2.
        const std::vector<double> mean = figures(e.at("mean"));
        const std::vector<double> se = figures(e.at("standard_error"));
        for (size_t f = 0; f < mean.size(); ++f) {
            EXPECT_NEAR(mean[f], (a[f] + b[f]) / 2, 1e-12) << g["label"] << " " << kFigureNames[f];
            EXPECT_NEAR(se[f], std::abs(a[f] - b[f]) / 2, 1e-12) << kFigureNames[f];
        }
        EXPECT_NEAR(e.at("temporal_error").get<double>(), (temporal[0] + temporal[1]) / 2, 1e-12);
        // Frame times and pass executions are over the measured frames of both seeds.
        for (const json& p : g.at("passes")) {
            if (p.at("name") == "pt") {
                EXPECT_EQ(p.at("executions"), 4);
            }
        }
    }
    EXPECT_NE(perSeed[1][0][0], perSeed[0][0][0]) << "the `set` did not change the output";

    EXPECT_FALSE(j["graphs"][0].contains("difference")) << "the first graph is the baseline";
    for (size_t g = 1; g < 3; ++g) {
        const json& d = j["graphs"][g].at("difference");
        EXPECT_EQ(d.at("against"), "spp 1");
        for (size_t f = 0; f < 7; ++f) {
            const json& fig = d.at("figures").at(kFigureNames[f]);
            std::vector<double> diffs;
            for (size_t s = 0; s < 2; ++s) {
                diffs.push_back(perSeed[g][s][f] * scaleOf(f) - perSeed[0][s][f] * scaleOf(f));
                EXPECT_NEAR(fig.at("seeds")[s].get<double>(), diffs[s], 1e-12);
            }
            const double mean = (diffs[0] + diffs[1]) / 2, se = std::abs(diffs[0] - diffs[1]) / 2;
            EXPECT_NEAR(fig.at("mean").get<double>(), mean, 1e-12) << g << " " << kFigureNames[f];
            EXPECT_NEAR(fig.at("standard_error").get<double>(), se, 1e-12);
            EXPECT_EQ(fig.at("significant"), std::abs(mean) > 2 * se);
            if (g == 2) {  // the same graph twice: the same samples, no difference, no flag
                EXPECT_EQ(fig.at("mean").get<double>(), 0.0) << kFigureNames[f];
                EXPECT_EQ(fig.at("significant"), false) << kFigureNames[f];
            }
        }
    }

    const std::string csv = readText(tmp / "out" / "bench.csv");
    EXPECT_TRUE(contains(csv, ",pareto,seeds,rmse_se,")) << csv;
    EXPECT_TRUE(contains(csv, ",diff_rmse_0_5deg,diff_rmse_0_5deg_se,diff_rmse_0_5deg_significant"))
        << csv;
    EXPECT_TRUE(contains(csv, ",1 2,")) << csv;
    const std::string md = readText(tmp / "out" / "bench.md");
    for (const char* s : {"## Difference against spp 1 (paired over seeds)", "## Each seed",
                          "| spp 1 again | 0.00000 ± 0.00000 |", " ± "})
        EXPECT_TRUE(contains(md, s)) << s << "\n" << md;
}

TEST(CliBenchSeeds, OneSeedWritesNoSeedFigures) {
    // `seeds` with one entry is `seed`: no per-seed errors, no standard error, no difference.
    TempDir tmp;
    json spec = seedsBench();
    spec["size"] = {16, 16};
    spec["frames"] = 2;
    spec["seeds"] = {5};
    spec["graphs"].erase(2);
    Result r = benchSeeds(tmp, spec, "out");
    ASSERT_EQ(r.code, 0) << r.describe();
    const json j = json::parse(readText(tmp / "out" / "bench.json"));
    EXPECT_EQ(j.at("seed"), 5);
    EXPECT_FALSE(j.contains("seeds"));
    EXPECT_EQ(j.at("reference").at("seed"), 6);
    for (const json& g : j.at("graphs")) {
        EXPECT_FALSE(g.contains("difference"));
        EXPECT_TRUE(g.at("errors").contains("frames"));
        EXPECT_FALSE(g["errors"].contains("seeds"));
        EXPECT_FALSE(g["errors"].contains("standard_error"));
    }
    EXPECT_FALSE(contains(readText(tmp / "out" / "bench.csv"), "diff_")) << "new columns";
    const std::string md = readText(tmp / "out" / "bench.md");
    EXPECT_FALSE(contains(md, "paired over seeds")) << md;
    EXPECT_FALSE(contains(md, " ± ")) << md;
}
