// The statistics of `fovea bench` over several seeds (eval/bench/BenchSeeds.cpp, docs/bench.md
// "Several seeds") on numbers worked out by hand: the mean over the seeds, the standard error
// (sample standard deviation / sqrt(seeds)), the paired difference and its > 2 s.e. flag. The
// end-to-end run is tests/cli/CliBenchSeedsTests.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "eval/bench/Bench.h"

using nlohmann::json;
using namespace fovea::eval;

namespace {

// One seed's FrameErrors::json() as the bench writes it, reduced to the figures compared:
// RMSE (and RMSE % = 100 RMSE), three bands, optionally three layers.
json seedErrors(double rmse, const std::vector<double>& bands, double temporal,
                const std::vector<double>& layers = {}, json psnr = 20.0) {
    json mean = {
        {"rmse", rmse}, {"rmse_percent", 100 * rmse}, {"mse", rmse * rmse},    {"psnr_db", psnr},
        {"peak", 1.0},  {"rel_mse_epsilon", 0.01},    {"bands", json::array()}};
    const double edges[] = {0, 5, 20};
    for (size_t b = 0; b < bands.size(); ++b)
        mean["bands"].push_back({{"from", edges[b]},
                                 {"to", b + 1 < 3 ? json(edges[b + 1]) : json(nullptr)},
                                 {"pixels", 10 * (b + 1)},
                                 {"rmse", bands[b]}});
    if (!layers.empty()) {
        mean["layers"] = json::array();
        for (size_t l = 0; l < layers.size(); ++l)
            mean["layers"].push_back({{"layer", l == 0   ? "fovea"
                                                : l == 1 ? "middle"
                                                         : "outer"},
                                      {"unit", "pixels"},
                                      {"rmse", layers[l]}});
    }
    return {{"frames", json::array()},
            {"mean", mean},
            {"temporal_error", temporal},
            {"worst", {{"frame", 3}, {"rmse", rmse + 0.5}}}};
}

}  // namespace

TEST(BenchSeeds, MeanAndStandardErrorOverSeeds) {
    // RMSE 1, 2, 3, 6: mean 3; sample variance (4 + 1 + 0 + 9) / 3, s.e. sqrt(14 / 3) / 2.
    const std::vector<json> perSeed = {
        seedErrors(1, {0.1, 1, 5}, 0.5), seedErrors(2, {0.2, 1, 5}, 0.5),
        seedErrors(3, {0.3, 1, 5}, 1.5), seedErrors(6, {0.6, 1, 5}, 2.5)};
    const json e = combineSeedErrors({7, 8, 9, 10}, perSeed);
    const json& mean = e.at("mean");
    const json& se = e.at("standard_error");
    EXPECT_DOUBLE_EQ(mean.at("rmse").get<double>(), 3.0);
    EXPECT_DOUBLE_EQ(mean.at("rmse_percent").get<double>(), 300.0);
    EXPECT_DOUBLE_EQ(se.at("rmse").get<double>(), std::sqrt(14.0 / 3.0) / 2.0);
    EXPECT_DOUBLE_EQ(mean["bands"][0].at("rmse").get<double>(), 0.3);
    EXPECT_DOUBLE_EQ(se["bands"][0].at("rmse").get<double>(), std::sqrt(0.14 / 3.0) / 2.0);
    EXPECT_EQ(se["bands"][1].at("rmse").get<double>(), 0.0) << "equal in every seed";
    // What names a band is kept, not averaged or turned into a spread.
    EXPECT_EQ(se["bands"][1].at("from"), 5.0);
    EXPECT_EQ(se["bands"][2].at("to"), nullptr);
    EXPECT_EQ(se["bands"][2].at("pixels"), 30);
    EXPECT_EQ(se.at("peak"), 1.0);
    EXPECT_DOUBLE_EQ(e.at("temporal_error").get<double>(), 1.25);
    EXPECT_DOUBLE_EQ(e.at("temporal_error_standard_error").get<double>(),
                     std::sqrt((0.5625 * 2 + 0.0625 + 1.5625) / 3.0) / 2.0);
    // The worst frame of all seeds, with its seed; every seed's own errors with theirs.
    EXPECT_EQ(e.at("worst").at("seed"), 10);
    EXPECT_DOUBLE_EQ(e["worst"].at("rmse").get<double>(), 6.5);
    ASSERT_EQ(e.at("seeds").size(), 4u);
    EXPECT_EQ(e["seeds"][1].at("seed"), 8);
    EXPECT_EQ(e["seeds"][1].at("mean"), perSeed[1].at("mean"));
}

TEST(BenchSeeds, InfinitePsnrOfOneSeedMakesTheMeanInfinite) {
    const json e = combineSeedErrors(
        {1, 2}, {seedErrors(0, {0, 0, 0}, 0, {}, nullptr), seedErrors(1, {1, 1, 1}, 0, {}, 30.0)});
    EXPECT_EQ(e.at("mean").at("psnr_db"), nullptr);  // JSON null = +inf (identical images)
    fovea::eval::ImageMetrics a, b;
    a.psnr = INFINITY;
    b.psnr = 30;
    a.rmse = 1;
    b.rmse = 2;
    const fovea::eval::ImageMetrics m = meanOverSeeds({a, b});
    EXPECT_TRUE(std::isinf(m.psnr));
    EXPECT_DOUBLE_EQ(m.rmse, 1.5);
}

TEST(BenchSeeds, PairedDifferenceAndItsFlag) {
    const json first = combineSeedErrors({1, 2}, {seedErrors(1, {1, 1, 1}, 0, {0.1, 0.1, 0.1}),
                                                  seedErrors(2, {1, 1, 1}, 0, {0.1, 0.1, 0.1})});
    // Per seed graph - first: RMSE +1, +3 (mean 2, s.e. 1: within 2 s.e.); band 0 +2, +3 (mean
    // 2.5, s.e. 0.5: flagged); band 1 -1, +1 (mean 0); band 2 equal (0, no flag); layers: fovea
    // -0.05, -0.06 in RMSE, i.e. -5 and -6 RMSE % (mean -5.5, s.e. 0.5: flagged).
    const json graph = combineSeedErrors({1, 2}, {seedErrors(2, {3, 0, 1}, 0, {0.05, 0.1, 0.1}),
                                                  seedErrors(5, {4, 2, 1}, 0, {0.04, 0.1, 0.1})});
    const json d = pairedDifference(graph, first, "base");
    EXPECT_EQ(d.at("against"), "base");
    const json& f = d.at("figures");
    auto expectFigure = [&](const char* name, std::vector<double> seeds, double mean, double se,
                            bool significant) {
        SCOPED_TRACE(name);
        ASSERT_TRUE(f.contains(name));
        ASSERT_EQ(f[name].at("seeds").size(), seeds.size());
        for (size_t s = 0; s < seeds.size(); ++s)
            EXPECT_NEAR(f[name]["seeds"][s].get<double>(), seeds[s], 1e-12);
        EXPECT_NEAR(f[name].at("mean").get<double>(), mean, 1e-12);
        EXPECT_NEAR(f[name].at("standard_error").get<double>(), se, 1e-12);
        EXPECT_EQ(f[name].at("significant"), significant);
    };
    expectFigure("rmse", {1, 3}, 2, 1, false);
    expectFigure("rmse_percent", {100, 300}, 200, 100, false);
    expectFigure("rmse_0_5deg", {2, 3}, 2.5, 0.5, true);
    expectFigure("rmse_5_20deg", {-1, 1}, 0, 1, false);
    expectFigure("rmse_20deg_plus", {0, 0}, 0, 0, false);
    expectFigure("rmse_percent_fovea", {-5, -6}, -5.5, 0.5, true);
    expectFigure("rmse_percent_middle", {0, 0}, 0, 0, false);

    // A graph against itself: every difference 0, nothing flagged.
    for (const auto& [name, fig] : pairedDifference(first, first, "base").at("figures").items()) {
        EXPECT_EQ(fig.at("mean").get<double>(), 0.0) << name;
        EXPECT_EQ(fig.at("significant"), false) << name;
    }
    // A figure one graph lacks (no layers) is left out, not compared with zero.
    const json noLayers =
        combineSeedErrors({1, 2}, {seedErrors(1, {1, 1, 1}, 0), seedErrors(2, {1, 1, 1}, 0)});
    const json partial = pairedDifference(noLayers, first, "base").at("figures");
    EXPECT_TRUE(partial.contains("rmse_0_5deg"));
    EXPECT_FALSE(partial.contains("rmse_percent_fovea"));
}
