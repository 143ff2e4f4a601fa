// The evaluation protocol end to end (docs/benchmarks.md "the paper's protocol"): the
// reference's noise floor in `run --reference-noise` (0 for two identical references, > 0 for
// another seed), the worst frame of a per-frame printf-pattern reference, and `fovea bench`'s
// noise floor, per-layer errors, extra reference and Pareto flags. Tiny sizes (lavapipe).
#include "core/image/ImageIO.h"
#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

Result run(const fs::path& out, std::vector<std::string> extra, const std::string& frames = "3") {
    std::vector<std::string> args = {"run",   kDemoGraph.string(), "--out", out.string(), "--size",
                                     "32x32", "--frames",          frames};
    args.insert(args.end(), extra.begin(), extra.end());
    return cli(args);
}

json referenceOf(const fs::path& out) {
    return json::parse(readText(out / "report.json")).at("reference");
}

fs::path frameFile(const fs::path& dir, int f) {
    char name[48];
    std::snprintf(name, sizeof name, "acc.mean.frame%04d.exr", f);
    return dir / name;
}

}  // namespace

TEST(CliProtocol, NoiseFloorIsZeroForIdenticalReferencesAndPositiveForAnotherSeed) {
    TempDir tmp;
    Result a = run(tmp / "a", {"--save-frames", "all"});
    ASSERT_EQ(a.code, 0) << a.describe();
    Result b = run(tmp / "b", {"--save-frames", "all", "--seed", "7"});
    ASSERT_EQ(b.code, 0) << b.describe();
    const std::vector<std::string> compared = {"--reference-output", "acc.mean",
                                               "--save-frames",      "none",
                                               "--reference",        (tmp / "a").string()};

    auto same = compared;
    same.insert(same.end(), {"--reference-noise", (tmp / "a").string()});
    Result r = run(tmp / "same", same);
    ASSERT_EQ(r.code, 0) << r.describe();
    const json s = referenceOf(tmp / "same");
    EXPECT_EQ(s.at("noise_floor").at("mean").at("rmse").get<double>(), 0.0);
    EXPECT_EQ(s.at("mean").at("rmse_noise_corrected").get<double>(), 0.0);

    auto other = compared;
    other.insert(other.end(), {"--reference-noise", (tmp / "b").string()});
    r = run(tmp / "other", other);
    ASSERT_EQ(r.code, 0) << r.describe();
    const json o = referenceOf(tmp / "other");
    const json& floor = o.at("noise_floor");
    EXPECT_GT(floor.at("mean").at("rmse").get<double>(), 0.0);
    ASSERT_EQ(floor.at("frames").size(), 3u);
    for (const auto& f : floor["frames"]) EXPECT_GT(f.at("rmse").get<double>(), 0.0) << f;
    EXPECT_TRUE(contains(floor.at("path"), (tmp / "b").string()));
    // The run against itself: error 0, corrected 0 whatever the floor.
    EXPECT_EQ(o.at("mean").at("rmse").get<double>(), 0.0);
    EXPECT_EQ(o.at("mean").at("rmse_noise_corrected").get<double>(), 0.0);

    expectInputError(run(tmp / "bad", {"--reference-noise", (tmp / "a").string()}),
                     {"--reference-noise", "needs --reference"});
}

TEST(CliProtocol, WorstFrameOfAPatternReference) {
    TempDir tmp;
    Result a = run(tmp / "a", {"--save-frames", "all"});
    ASSERT_EQ(a.code, 0) << a.describe();
    // ref0000..ref0002.exr: the run's own frames, frame 1 off by 0.1 (worst), frame 2 by 0.02.
    for (int f = 0; f < 3; ++f) {
        auto img = fovea::image::readImage(frameFile(tmp / "a", f));
        const float offset = f == 1 ? 0.1f : (f == 2 ? 0.02f : 0.0f);
        for (size_t i = 0; i < img.pixels.size(); ++i)
            if (i % 4 != 3) img.pixels[i] += offset;
        char name[32];
        std::snprintf(name, sizeof name, "ref%04d.exr", f);
        fovea::image::writeExr(tmp / name, img);
    }
    Result r = run(tmp / "r", {"--reference", (tmp / "ref%04d.exr").string(), "--reference-output",
                               "acc.mean", "--save-frames", "none"});
    ASSERT_EQ(r.code, 0) << r.describe();
    const json ref = referenceOf(tmp / "r");
    EXPECT_EQ(ref.at("mode"), "per-frame");
    ASSERT_EQ(ref.at("frames").size(), 3u);
    EXPECT_TRUE(contains(ref["frames"][1].at("reference"), "ref0001.exr"));
    EXPECT_EQ(ref.at("worst").at("frame"), 1);
    EXPECT_NEAR(ref["worst"].at("rmse").get<double>(), 0.1, 1e-6);
    EXPECT_NEAR(ref["frames"][2].at("rmse").get<double>(), 0.02, 1e-6);

    // A pattern without a file for a frame, or without one integer conversion: input errors.
    expectInputError(run(tmp / "m", {"--reference", (tmp / "ref%04d.exr").string()}, "4"),
                     {"--reference", "frame 3", "ref0003.exr"});
    expectInputError(run(tmp / "n", {"--reference", (tmp / "ref%s.exr").string()}),
                     {"--reference", "integer conversion"});
}

TEST(CliProtocol, BenchReportsFloorLayersExtraReferenceAndPareto) {
    TempDir tmp;
    const fs::path demo = kRepo / "graphs" / "demo.json";
    json spec = {{"version", 1},
                 {"name", "protocol"},
                 {"scene", "builtin:cornell"},
                 {"size", {32, 32}},
                 {"stereo", true},
                 {"frames", 3},
                 {"warmup", 1},
                 {"output", "acc.mean"},
                 {"reference", {{"render", {{"spp", 8}}}}},
                 {"noise_floor", "render"},
                 {"layers", {{"r0", 4}, {"r1", 8}}},
                 {"graphs",
                  {{{"label", "spp 1"}, {"file", demo.string()}, {"set", {"pt.spp=1"}}},
                   {{"label", "spp 4"}, {"file", demo.string()}, {"set", {"pt.spp=4"}}}}}};
    writeText(tmp / "a.json", spec.dump(2));
    Result r = cli({"bench", (tmp / "a.json").string(), "--out", (tmp / "a").string(), "--quiet"});
    ASSERT_EQ(r.code, 0) << r.describe();
    const json j = json::parse(readText(tmp / "a" / "bench.json"));
    const json& floor = j.at("noise_floor").at("reference");
    EXPECT_GT(floor.at("mean").at("rmse").get<double>(), 0.0) << "two seeds differ";
    EXPECT_EQ(j.at("layers").at("r0"), 4.0);
    size_t pareto = 0;
    for (const json& g : j.at("graphs")) {
        const json& layers = g.at("errors").at("mean").at("layers");
        ASSERT_EQ(layers.size(), 3u);
        uint64_t pixels = 0;
        for (const json& l : layers) pixels += l.at("pixels").get<uint64_t>();
        EXPECT_EQ(pixels, 32u * 32u);
        EXPECT_TRUE(g.at("errors").at("worst").at("frame").is_number());
        pareto += g.at("pareto").get<bool>() ? 1 : 0;
    }
    EXPECT_GE(pareto, 1u);
    const std::string svg = readText(tmp / "a" / "bench.svg");
    size_t rings = 0;
    for (size_t at = svg.find("class=\"pareto\""); at != std::string::npos;
         at = svg.find("class=\"pareto\"", at + 1))
        ++rings;
    EXPECT_EQ(rings, pareto);
    const std::string md = readText(tmp / "a" / "bench.md");
    for (const char* s : {"noise floor: 2nd reference", "above the reference noise", "Worst frame",
                          "fovea (d <= 4 px)", "Pareto"})
        EXPECT_TRUE(contains(md, s)) << s << "\n" << md;

    // The rendered reference as a second reference, with itself as its floor: floor 0 and the
    // same errors as against the bench's own reference.
    const std::string rendered = (tmp / "a" / "reference" / "reference.exr").string();
    spec["noise_floor"] = (tmp / "a" / "reference_noise_floor" / "reference.exr").string();
    spec["reference"] = rendered;
    spec["also_against"] = {
        {{"label", "copy"}, {"reference", rendered}, {"noise_floor", rendered}}};
    writeText(tmp / "b.json", spec.dump(2));
    r = cli({"bench", (tmp / "b.json").string(), "--out", (tmp / "b").string(), "--quiet"});
    ASSERT_EQ(r.code, 0) << r.describe();
    const json k = json::parse(readText(tmp / "b" / "bench.json"));
    EXPECT_EQ(k.at("noise_floor").at("copy").at("mean").at("rmse").get<double>(), 0.0);
    EXPECT_EQ(k["noise_floor"]["reference"]["mean"]["rmse"], floor["mean"]["rmse"]);
    for (size_t g = 0; g < 2; ++g) {
        const json& graph = k.at("graphs")[g];
        EXPECT_EQ(graph.at("also_against").at("copy").at("mean").at("rmse"),
                  graph.at("errors").at("mean").at("rmse"));
        EXPECT_EQ(graph["errors"]["mean"]["rmse"], j["graphs"][g]["errors"]["mean"]["rmse"]);
    }
    EXPECT_TRUE(contains(readText(tmp / "b" / "bench.md"), "Error against the reference 'copy'"));
}
