// `fovea bench BENCH.json --out DIR` end to end (docs/bench.md): a tiny bench of two graphs
// writes bench.json/.csv/.md/.svg with the documented keys, the baseline's speedup is 1, the plot
// has one point per graph, a rendered reference is cached and reused, a file reference gives the
// same errors, and bad bench files exit 2 naming the JSON pointer. Tiny sizes (lavapipe).
#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

json tinyBench() {
    return {{"version", 1},
            {"name", "tiny"},
            {"scene", "builtin:cornell"},
            {"size", {32, 32}},
            {"frames", 3},
            {"warmup", 1},
            {"output", "acc.mean"},
            {"reference", {{"render", {{"spp", 8}}}}},
            {"graphs",
             {{{"label", "spp 1"}, {"file", kDemoGraph.string()}, {"set", {"pt.spp=1"}}},
              {{"label", "spp 2"}, {"file", kDemoGraph.string()}, {"set", {"pt.spp=2"}}}}}};
}

Result bench(const TempDir& tmp, const json& spec, const std::string& out,
             std::vector<std::string> extra = {}) {
    const fs::path file = tmp / (out + ".bench.json");
    writeText(file, spec.dump(2));
    std::vector<std::string> args = {"bench", file.string(), "--out", (tmp / out).string(),
                                     "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    return cli(args);
}

size_t countOf(const std::string& text, const std::string& needle) {
    size_t n = 0;
    for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1))
        ++n;
    return n;
}

}  // namespace

TEST(CliBench, TinyBenchWritesEveryFile) {
    TempDir tmp;
    Result r = bench(tmp, tinyBench(), "out");
    ASSERT_EQ(r.code, 0) << r.describe();
    const fs::path out = tmp / "out";
    for (const char* f : {"bench.json", "bench.csv", "bench.md", "bench.svg"})
        ASSERT_TRUE(fs::is_regular_file(out / f)) << f << "\n" << r.describe();

    const json j = json::parse(readText(out / "bench.json"));
    EXPECT_EQ(j.at("bench_version"), 1);
    EXPECT_EQ(j.at("size"), json::array({32, 32}));
    EXPECT_EQ(j.at("frames"), 3);
    EXPECT_EQ(j.at("warmup"), 1);
    EXPECT_EQ(j.at("reference").at("source"), "render");
    EXPECT_EQ(j["reference"].at("cached"), false);
    EXPECT_EQ(j["reference"].at("mode"), "single");
    ASSERT_EQ(j.at("graphs").size(), 2u);
    const json& base = j["graphs"][0];
    const json& two = j["graphs"][1];
    EXPECT_EQ(base.at("label"), "spp 1");
    EXPECT_EQ(base.at("speedup").get<double>(), 1.0) << "the baseline is the first graph";
    EXPECT_NEAR(two.at("speedup").get<double>(),
                base["frame_ms"]["median"].get<double>() / two["frame_ms"]["median"].get<double>(),
                1e-9);
    for (const json& g : j["graphs"]) {
        EXPECT_EQ(g.at("output"), "acc.mean");
        expectStats(g.at("frame_ms"), "frame_ms");
        const json& e = g.at("errors");
        ASSERT_EQ(e.at("frames").size(), 2u) << "frames after the warm-up only";
        EXPECT_EQ(e["frames"][0].at("frame"), 1);
        for (const char* key : {"rmse_percent", "psnr_db", "ssim", "rel_mse"})
            EXPECT_TRUE(e.at("mean").at(key).is_number()) << key;
        EXPECT_GT(e["mean"]["rmse_percent"].get<double>(), 0.0);
        EXPECT_TRUE(e.at("temporal_error").is_number());
        std::set<std::string> passes;
        for (const json& p : g.at("passes")) {
            passes.insert(p.at("name"));
            expectStats(p.at("gpu_ms"), "passes.gpu_ms");
        }
        EXPECT_EQ(passes, (std::set<std::string>{"gb", "pt", "acc", "tm"}));
    }

    const std::string csv = readText(out / "bench.csv");
    EXPECT_EQ(countOf(csv, "\n"), 3u) << csv;
    EXPECT_TRUE(contains(csv, "label,file,output,frame_ms_median")) << csv;
    const std::string md = readText(out / "bench.md");
    for (const char* s : {"| spp 1 |", "| spp 2 |", "Speedup", "RMSE %", "PSNR", "SSIM",
                          "Temporal error", "| pt | PathTrace |"})
        EXPECT_TRUE(contains(md, s)) << s << "\n" << md;

    const std::string svg = readText(out / "bench.svg");
    EXPECT_EQ(svg.rfind("<svg", 0), 0u) << svg.substr(0, 80);
    EXPECT_TRUE(contains(svg, "</svg>"));
    EXPECT_EQ(countOf(svg, "class=\"point\""), 2u);
    EXPECT_EQ(countOf(svg, "<circle"), countOf(svg, "</circle>"));
    EXPECT_TRUE(contains(svg, ">spp 1</text>") && contains(svg, ">spp 2</text>"));
    EXPECT_GE(countOf(svg, "class=\"xtick\""), 2u);
    EXPECT_GE(countOf(svg, "class=\"ytick\""), 2u);

    // A non-empty DIR needs --overwrite; with it the rendered reference is reused.
    expectInputError(bench(tmp, tinyBench(), "out"), {"--out", "--overwrite"});
    Result again = bench(tmp, tinyBench(), "out", {"--overwrite"});
    ASSERT_EQ(again.code, 0) << again.describe();
    const json j2 = json::parse(readText(out / "bench.json"));
    EXPECT_EQ(j2["reference"].at("cached"), true);

    // The cached reference as a file reference: the same errors (deterministic runs).
    json spec = tinyBench();
    spec["reference"] = (out / "reference" / "reference.exr").string();
    Result file = bench(tmp, spec, "file");
    ASSERT_EQ(file.code, 0) << file.describe();
    const json j3 = json::parse(readText(tmp / "file" / "bench.json"));
    EXPECT_EQ(j3["reference"].at("source"), "file");
    for (size_t g = 0; g < 2; ++g)
        EXPECT_EQ(j3["graphs"][g]["errors"]["mean"]["rmse"],
                  j["graphs"][g]["errors"]["mean"]["rmse"]);
}

// ꟻLIP in a bench: on by default (HDR for the float output, in bench.json's means, bench.csv and
// bench.md), LDR at the camera's pixels per degree when the bench says so, absent with false.
TEST(CliBench, FlipFiguresFollowTheBenchFile) {
    TempDir tmp;
    json spec = tinyBench();
    spec["graphs"] = json::array({spec["graphs"][0]});
    ASSERT_EQ(bench(tmp, spec, "on").code, 0);
    const json on = json::parse(readText(tmp / "on" / "bench.json"));
    const json& errors = on.at("graphs")[0].at("errors");
    EXPECT_EQ(errors.at("flip").at("mode"), "hdr");
    const double mean = errors.at("mean").at("flip_mean").get<double>();
    EXPECT_GT(mean, 0.0);
    EXPECT_LT(mean, 1.0);
    EXPECT_TRUE(errors.at("mean").at("bands")[0].contains("flip_mean"));
    EXPECT_TRUE(contains(readText(tmp / "on" / "bench.csv"), ",temporal_error,flip_mean,"));
    EXPECT_TRUE(contains(readText(tmp / "on" / "bench.md"), "| ꟻLIP |"));

    spec["flip"] = {{"mode", "ldr"}, {"ppd", "camera"}};
    ASSERT_EQ(bench(tmp, spec, "camera").code, 0);
    const json camera = json::parse(readText(tmp / "camera" / "bench.json"));
    const json& c = camera.at("graphs")[0].at("errors");
    EXPECT_EQ(c.at("flip").at("mode"), "ldr");
    EXPECT_LT(c.at("flip").at("pixels_per_degree").get<double>(), 5.0);  // 32 px over ~40 deg
    EXPECT_NE(c.at("mean").at("flip_mean").get<double>(), mean);

    spec["flip"] = false;
    ASSERT_EQ(bench(tmp, spec, "off").code, 0);
    const json off = json::parse(readText(tmp / "off" / "bench.json"));
    EXPECT_FALSE(off.at("graphs")[0].at("errors").at("mean").contains("flip_mean"));
    EXPECT_FALSE(off.at("graphs")[0].at("errors").contains("flip"));
}

TEST(CliBench, BadBenchFilesNameThePointer) {
    TempDir tmp;
    struct Case {
        std::function<void(json&)> edit;
        std::vector<std::string> fragments;
    };
    const std::vector<Case> cases = {
        {[](json& j) { j.erase("frames"); }, {"missing field 'frames'"}},
        {[](json& j) { j["size"] = "32x32"; }, {"/size", "[width, height]"}},
        {[](json& j) { j["frames"] = "3"; }, {"/frames", "integer"}},
        {[](json& j) { j["warmup"] = 3; }, {"/warmup", "no measured frame"}},
        {[](json& j) { j["sun"] = "yes"; }, {"/sun", "true or false"}},
        {[](json& j) { j["graphs"][1]["file"] = "nope.json"; }, {"/graphs/1/file", "nope.json"}},
        {[](json& j) { j["graphs"][0]["set"] = {"pt.spq=1"}; }, {"/graphs/0/set", "spq"}},
        {[](json& j) { j["graphs"][0]["label"] = 7; }, {"/graphs/0/label", "string"}},
        {[](json& j) { j["graphz"] = j["graphs"]; }, {"/graphz", "did you mean 'graphs'"}},
        {[](json& j) { j["reference"] = 3; }, {"/reference", "render"}},
        {[](json& j) { j["reference"] = "missing.exr"; }, {"/reference", "missing.exr"}},
        {[](json& j) { j["reference"]["render"]["spp"] = 0; }, {"/reference/render/spp"}},
        {[](json& j) { j["graphs"] = json::array(); }, {"/graphs", "non-empty"}},
        // The protocol's keys (docs/bench.md): noise floor, extra references, layer radii.
        {[](json& j) { j["noise_floor"] = 3; }, {"/noise_floor", "second reference"}},
        {[](json& j) {
             j["reference"] = "r.exr";
             j["noise_floor"] = "render";
         },
         {"/noise_floor", "rendered /reference"}},
        {[](json& j) { j["also_against"] = "x"; }, {"/also_against", "array"}},
        {[](json& j) {
             j["also_against"] = {{{"reference", "x.exr"}}};
         },
         {"/also_against/0", "missing field 'label'"}},
        {[](json& j) {
             j["also_against"] = {{{"label", "a"}, {"reference", "none.exr"}}};
         },
         {"/also_against/0/reference", "none.exr"}},
        {[](json& j) {
             j["also_against"] = {{{"label", "a"}, {"referenc", "x.exr"}}};
         },
         {"/also_against/0/referenc", "did you mean 'reference'"}},
        {[](json& j) {
             j["layers"] = {{"r0", 8}, {"r1", 4}};
         },
         {"/layers/r1", "smaller than r0"}},
        {[](json& j) {
             j["layers"] = {{"r0", 8}, {"r1", 16}, {"unit", "cm"}};
         },
         {"/layers/unit", "degrees"}},
        {[](json& j) {
             j["layers"] = {{"r0", "8"}, {"r1", 16}};
         },
         {"/layers/r0", "number"}},
        {[](json& j) { j["noise_floor"] = "nofloor.exr"; }, {"/noise_floor", "nofloor.exr"}},
        // Several seeds (docs/bench.md): a non-empty array of distinct integers, not with `seed`.
        {[](json& j) {
             j["seed"] = 1;
             j["seeds"] = {1, 2};
         },
         {"/seeds", "not both"}},
        {[](json& j) { j["seeds"] = json::array(); }, {"/seeds", "non-empty array"}},
        {[](json& j) { j["seeds"] = 3; }, {"/seeds", "non-empty array"}},
        {[](json& j) {
             j["seeds"] = {1, 2, 1};
         },
         {"/seeds/2", "seed 1 is given twice"}},
        {[](json& j) {
             j["seeds"] = {1, "2"};
         },
         {"/seeds/1", "integer"}},
        {[](json& j) {
             j["seeds"] = {1, 2.5};
         },
         {"/seeds/1", "integer"}},
        {[](json& j) { j["seeds"] = {-1}; }, {"/seeds/0", "integer"}},
        {[](json& j) {
             j["seedz"] = {1, 2};
         },
         {"/seedz", "did you mean"}},
        // ꟻLIP (docs/bench.md "flip"): a boolean or {"mode", "ppd"}.
        {[](json& j) { j["flip"] = "yes"; }, {"/flip", "true, false"}},
        {[](json& j) {
             j["flip"] = {{"mode", "sdr"}};
         },
         {"/flip/mode", "\"ldr\""}},
        {[](json& j) {
             j["flip"] = {{"ppd", -2}};
         },
         {"/flip/ppd", "camera"}},
        {[](json& j) {
             j["flip"] = {{"ppd", "eye"}};
         },
         {"/flip/ppd", "camera"}},
        {[](json& j) {
             j["flip"] = {{"pdd", 30}};
         },
         {"/flip/pdd", "did you mean 'ppd'"}},
    };
    for (size_t i = 0; i < cases.size(); ++i) {
        json spec = tinyBench();
        cases[i].edit(spec);
        const std::string name = "case" + std::to_string(i);
        Result r = bench(tmp, spec, name);
        std::vector<std::string> fragments = cases[i].fragments;
        fragments.push_back((tmp / (name + ".bench.json")).string());
        EXPECT_EQ(r.code, 2) << "case " << i << "\n" << r.describe();
        for (const auto& f : fragments)
            EXPECT_TRUE(contains(r.err, f)) << "case " << i << ": '" << f << "'\n" << r.describe();
        EXPECT_FALSE(fs::exists(tmp / name / "bench.json")) << "case " << i;
    }
    writeText(tmp / "broken.json", "{ not json");
    Result broken = cli({"bench", (tmp / "broken.json").string(), "--out", (tmp / "b").string()});
    expectInputError(broken,
                     {(tmp / "broken.json").string(), "line 1, column 4", "JSON syntax error"});
}

TEST(CliBench, ShippedBenchFilesParse) {
    // --out names a regular file: the run stops at the --out check, which comes right after the
    // bench file parsed (no device, no rendering).
    TempDir tmp;
    writeText(tmp / "file", "x");
    size_t count = 0;
    for (const auto& e : fs::directory_iterator(kRepo / "graphs" / "benches")) {
        if (e.path().extension() != ".json") continue;
        ++count;
        Result r = cli({"bench", e.path().string(), "--out", (tmp / "file").string()});
        expectInputError(r, {"--out", "is not a directory"});
        EXPECT_FALSE(contains(r.err, e.path().filename().string())) << r.describe();
    }
    EXPECT_GE(count, 1u);
}

// docs/benchmarks.md's figures come from scripts/benchmarks.sh: every bench file it runs exists
// (and, being in graphs/benches, parses: ShippedBenchFilesParse), every table of its --list is
// one the script accepts, and the page names the script.
TEST(CliBench, BenchmarksScriptNamesShippedBenchFiles) {
    TempDir tmp;
    const std::string script = (kRepo / "scripts" / "benchmarks.sh").string();
    const int status = std::system(("bash " + shellQuote(script) + " --list > " +
                                    shellQuote((tmp / "list").string()) + " 2>&1")
                                       .c_str());
    ASSERT_EQ(status, 0) << readText(tmp / "list");
    std::istringstream lines(readText(tmp / "list"));
    std::string table, file;
    std::set<std::string> tables;
    size_t count = 0;
    while (lines >> table >> file) {
        ++count;
        tables.insert(table);
        EXPECT_EQ(file.rfind("graphs/benches/", 0), 0u) << file;
        EXPECT_TRUE(fs::is_regular_file(kRepo / file)) << table << " " << file;
    }
    EXPECT_GE(count, 10u);
    EXPECT_TRUE(tables.count("peres") && tables.count("koskela") && tables.count("vp"));
    const std::string page = readText(kRepo / "docs" / "benchmarks.md");
    EXPECT_TRUE(contains(page, "scripts/benchmarks.sh"));
    EXPECT_LT(std::count(page.begin(), page.end(), '\n'), 400) << "docs/benchmarks.md is a summary";
}

TEST(CliBench, BenchCameraOverridesTheGraphsDefaultCamera) {
    // The bench decides the camera: without one every graph sees the scene's still camera, even
    // a graph whose defaults.camera names a path (here one that does not exist, so using it
    // would fail the run). graphs/peres_*.json default to a moving camera path.
    TempDir tmp;
    json graph = json::parse(readText(kDemoGraph));
    graph["defaults"]["camera"] = "no_such_camera_path.json";
    const fs::path file = tmp / "moving.json";
    writeText(file, graph.dump(2));
    json spec = tinyBench();
    spec["size"] = {16, 16};
    spec["reference"] = {{"render", {{"spp", 2}}}};
    spec["graphs"] = {{{"label", "moving"}, {"file", file.string()}}};
    Result r = bench(tmp, spec, "out");
    ASSERT_EQ(r.code, 0) << r.describe();
    EXPECT_EQ(json::parse(readText(tmp / "out" / "bench.json")).at("camera"), "still");
    // `fovea run` itself does use the graph's camera path (and names the missing file).
    Result run = cli({"run", file.string(), "--size", "16x16", "--frames", "1", "--out",
                      (tmp / "run").string(), "--quiet"});
    EXPECT_NE(run.code, 0);
    EXPECT_TRUE(contains(run.err, "no_such_camera_path.json")) << run.describe();
}

TEST(CliBench, SunLightsAGltfWithoutLightsForGraphsAndReference) {
    // tinygltf's cube has no light: without `sun` graph and reference are black (error 0); with
    // it both are lit by run --sun's light, so the error is that of a 1-spp image against 2 spp.
    TempDir tmp;
    json spec = tinyBench();
    spec["scene"] = (kRepo / ".." / "shared" / "scenes" / "tinygltf-cube" / "Cube.gltf").string();
    spec["size"] = {16, 16};
    spec["frames"] = 2;
    spec["reference"] = {{"render", {{"spp", 2}}}};
    spec["graphs"] = {{{"label", "a"}, {"file", kDemoGraph.string()}}};
    double rmse[2] = {};
    for (bool sun : {false, true}) {
        spec["sun"] = sun;
        const std::string out = sun ? "sun" : "dark";
        Result r = bench(tmp, spec, out);
        ASSERT_EQ(r.code, 0) << r.describe();
        const json j = json::parse(readText(tmp / out / "bench.json"));
        EXPECT_EQ(j.at("sun"), sun);
        rmse[sun] = j["graphs"][0]["errors"]["mean"]["rmse"].get<double>();
    }
    EXPECT_EQ(rmse[0], 0.0);
    EXPECT_GT(rmse[1], 1e-3);
}
