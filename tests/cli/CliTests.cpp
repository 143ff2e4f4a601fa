// End-to-end tests of the `fovea` executable (apps/fovea): exit codes (0 ok, 1 runtime failure,
// 2 bad input or usage), report.json, written images, --set overrides, input errors naming the
// file or flag, validate over every shipped graph, `passes --json`, --help, determinism.
//
// Every test spawns FOVEA_EXE with stdout/stderr captured to files in a per-test temporary
// directory (removed afterwards). GPU runs are kept tiny (32x32, 2 frames): the suite runs on
// lavapipe. FOVEA_VALIDATION=1 in the environment (set by ctest) is inherited by the children.
#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

// --- run: the documented report and the written images ---------------------------------------

TEST(CliRun, DemoWritesReportAndImages) {
    TempDir tmp;
    const fs::path out = tmp / "out";
    Result r = runSmall(kDemo, out);
    ASSERT_EQ(r.code, 0) << r.describe();

    ASSERT_TRUE(fs::is_regular_file(out / "report.json")) << r.describe();
    json report = json::parse(readText(out / "report.json"), nullptr, false);
    ASSERT_FALSE(report.is_discarded()) << readText(out / "report.json");

    EXPECT_EQ(report.at("report_version"), 3);
    EXPECT_FALSE(report.contains("reference")) << "only with --reference";
    ASSERT_TRUE(report.at("fovea_version").is_string());
    EXPECT_FALSE(report["fovea_version"].get<std::string>().empty());
    EXPECT_EQ(report.at("graph"), kDemo.string());
    EXPECT_EQ(report.at("scene"), "none");
    EXPECT_TRUE(report.at("build_ms").is_number());
    EXPECT_GT(report.at("build_ms").get<double>(), 0.0);
    ASSERT_TRUE(report.at("device").is_object());
    ASSERT_TRUE(report["device"].at("name").is_string());
    ASSERT_TRUE(report["device"].at("driver").is_string());
    EXPECT_FALSE(report["device"]["name"].get<std::string>().empty());
    EXPECT_FALSE(report["device"]["driver"].get<std::string>().empty());
    EXPECT_EQ(report.at("size"), json::array({32, 32}));
    EXPECT_EQ(report.at("frames"), 2);
    EXPECT_EQ(report.at("seed"), 1);  // the graph's default

    // Passes: every pass of the graph, in plan order, with a known status and GPU timings.
    const json& passes = report.at("passes");
    ASSERT_TRUE(passes.is_array());
    std::map<std::string, json> byName;
    for (const auto& p : passes) {
        ASSERT_TRUE(p.at("name").is_string()) << p;
        ASSERT_TRUE(p.at("type").is_string()) << p;
        ASSERT_TRUE(p.at("status").is_string()) << p;
        ASSERT_TRUE(p.at("reason").is_string()) << p;
        static const std::set<std::string> kStatuses = {"executed", "culled", "skipped", "cached",
                                                        "bypassed"};
        EXPECT_TRUE(kStatuses.count(p["status"])) << p;
        expectStats(p.at("gpu_ms"), "passes[" + p["name"].get<std::string>() + "].gpu_ms");
        byName[p["name"]] = p;
    }
    ASSERT_EQ(byName.size(), 4u) << passes;
    // File order (docs/report-format.md), culled passes included.
    ASSERT_EQ(passes.size(), 4u);
    EXPECT_EQ(passes[0]["name"], "noise");
    EXPECT_EQ(passes[1]["name"], "acc");
    EXPECT_EQ(passes[2]["name"], "gradient");
    EXPECT_EQ(passes[3]["name"], "tm");
    EXPECT_EQ(byName["noise"]["type"], "ImageSource");
    EXPECT_EQ(byName["acc"]["type"], "Accumulate");
    EXPECT_EQ(byName["gradient"]["type"], "ImageSource");
    EXPECT_EQ(byName["tm"]["type"], "Tonemap");
    // Animated noise and the accumulator run every frame; the static gradient is cached on the
    // second frame (status is that of the last frame).
    EXPECT_EQ(byName["noise"]["status"], "executed");
    EXPECT_EQ(byName["acc"]["status"], "executed");
    EXPECT_EQ(byName["gradient"]["status"], "cached");
    EXPECT_EQ(byName["noise"]["reason"], "");
    EXPECT_FALSE(byName["gradient"]["reason"].get<std::string>().empty());
    EXPECT_EQ(byName["noise"]["executions"], 2);
    EXPECT_EQ(byName["acc"]["executions"], 2);
    EXPECT_EQ(byName["gradient"]["executions"], 1);
    EXPECT_GT(byName["acc"]["gpu_ms"]["max"].get<double>(), 0.0);

    const json& memory = report.at("memory");
    for (const char* key : {"transient_bytes", "transient_bytes_without_aliasing",
                            "persistent_bytes", "history_bytes"}) {
        ASSERT_TRUE(memory.contains(key) && memory[key].is_number_unsigned()) << key << memory;
    }
    EXPECT_LE(memory["history_bytes"].get<uint64_t>(), memory["persistent_bytes"].get<uint64_t>());
    EXPECT_LE(memory["transient_bytes"].get<uint64_t>(),
              memory["transient_bytes_without_aliasing"].get<uint64_t>());
    // At least the two marked outputs (outputs are persistent): 32*32*16 + 32*32*4 bytes.
    EXPECT_GE(memory["persistent_bytes"].get<uint64_t>(), 32u * 32u * (16u + 4u)) << memory;

    expectStats(report.at("frame_ms"), "frame_ms");
    expectStats(report.at("frame_cpu_ms"), "frame_cpu_ms");
    expectStats(report.at("executor_overhead_cpu_ms"), "executor_overhead_cpu_ms");
    EXPECT_GT(report["frame_ms"]["max"].get<double>(), 0.0);

    // Outputs: EXR + PNG per marked output, last frame only (the default --save-frames), named
    // with the frame number because more than one frame ran.
    const std::set<std::string> expected = {"acc.mean.frame0001.exr", "acc.mean.frame0001.png",
                                            "tm.ldr.frame0001.exr", "tm.ldr.frame0001.png"};
    // In the order written: per marked output, .exr then .png.
    EXPECT_EQ(report.at("outputs"),
              json(std::vector<std::string>(expected.begin(), expected.end())));
    std::set<std::string> onDisk;
    for (const auto& e : fs::directory_iterator(out)) onDisk.insert(e.path().filename().string());
    std::set<std::string> expectedOnDisk = expected;
    expectedOnDisk.insert("report.json");
    EXPECT_EQ(onDisk, expectedOnDisk);
    for (const auto& name : expected) {
        auto image = ::fovea::image::readImage(out / name);
        EXPECT_EQ(image.width, 32u) << name;
        EXPECT_EQ(image.height, 32u) << name;
        for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v)) << name;
    }
    // Sanity of the content: the mean of uniform noise over 2 frames is inside [0,1), and not
    // constant; the tone-mapped gradient is in [0,1].
    auto mean = pixels(out / "acc.mean.frame0001.exr");
    auto [lo, hi] = std::minmax_element(mean.begin(), mean.end());
    EXPECT_GE(*lo, 0.0f);
    EXPECT_LE(*hi, 1.0f);
    EXPECT_LT(*lo, *hi);
    for (float v : pixels(out / "tm.ldr.frame0001.exr")) {
        EXPECT_GE(v, 0.0f);
        EXPECT_LE(v, 1.0f);
    }
}

TEST(CliRun, SaveFramesAllAndNone) {
    TempDir tmp;
    Result all = runSmall(kDemo, tmp / "all", {"--save-frames", "all", "--set", "tm.srgb=false"});
    ASSERT_EQ(all.code, 0) << all.describe();
    for (const char* name : {"acc.mean.frame0000.exr", "acc.mean.frame0001.exr",
                             "tm.ldr.frame0000.png", "tm.ldr.frame0001.png"})
        EXPECT_TRUE(fs::is_regular_file(tmp / "all" / name)) << name;

    Result none = cli({"run", kDemo.string(), "--out", (tmp / "none").string(), "--frames", "1",
                       "--size", "8x8", "--save-frames", "none"});
    ASSERT_EQ(none.code, 0) << none.describe();
    json report = json::parse(readText(tmp / "none" / "report.json"));
    EXPECT_EQ(report["outputs"], json::array());
    EXPECT_EQ(report["frames"], 1);
    EXPECT_EQ(report["size"], json::array({8, 8}));
    size_t files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(tmp / "none")) ++files;
    EXPECT_EQ(files, 1u);  // only report.json
}

// --set overrides reach the passes: constant noise source => its running mean is that constant.
TEST(CliRun, SetOverridesAreApplied) {
    TempDir tmp;
    Result r = runSmall(kDemo, tmp / "out",
                        {"--set", "noise.pattern=constant", "--set", "noise.value=[0.25,0.5,0.75]",
                         "--set", "tm.exposure=1"});
    ASSERT_EQ(r.code, 0) << r.describe();
    auto image = ::fovea::image::readImage(tmp / "out" / "acc.mean.frame0001.exr");
    ASSERT_EQ(image.pixels.size(), 32u * 32u * 4u);
    for (size_t p = 0; p < 32u * 32u; ++p) {
        ASSERT_FLOAT_EQ(image.pixels[p * 4 + 0], 0.25f) << "pixel " << p;
        ASSERT_FLOAT_EQ(image.pixels[p * 4 + 1], 0.5f) << "pixel " << p;
        ASSERT_FLOAT_EQ(image.pixels[p * 4 + 2], 0.75f) << "pixel " << p;
    }
    // The override is for this run only: the file is unchanged.
    EXPECT_TRUE(contains(readText(kDemo), R"("pattern": "noise")"));
}

// Same graph, same seed => bit-identical images; another seed => different noise. (Pixels are
// compared, not files: an encoder may store a write time in a header.)
TEST(CliRun, SameSeedIsBitIdentical) {
    TempDir tmp;
    Result a = runSmall(kDemo, tmp / "a", {"--seed", "7"});
    Result b = runSmall(kDemo, tmp / "b", {"--seed", "7"});
    Result c = runSmall(kDemo, tmp / "c", {"--seed", "8"});
    ASSERT_EQ(a.code, 0) << a.describe();
    ASSERT_EQ(b.code, 0) << b.describe();
    ASSERT_EQ(c.code, 0) << c.describe();
    for (const char* name : {"acc.mean.frame0001.exr", "tm.ldr.frame0001.exr"}) {
        auto pa = pixels(tmp / "a" / name), pb = pixels(tmp / "b" / name);
        ASSERT_EQ(pa.size(), pb.size()) << name;
        EXPECT_EQ(std::memcmp(pa.data(), pb.data(), pa.size() * sizeof(float)), 0)
            << name << " differs between two runs with --seed 7";
    }
    EXPECT_NE(pixels(tmp / "a" / "acc.mean.frame0001.exr"),
              pixels(tmp / "c" / "acc.mean.frame0001.exr"))
        << "--seed had no effect on the noise";
    EXPECT_EQ(json::parse(readText(tmp / "a" / "report.json"))["seed"], 7);
}

// --out naming a non-empty directory: refused without --overwrite, user's files untouched;
// with --overwrite the run writes its files next to them.
TEST(CliRun, NonEmptyOutDirNeedsOverwrite) {
    TempDir tmp;
    const fs::path out = tmp / "out";
    fs::create_directories(out);
    writeText(out / "precious.txt", "user data");

    Result refused = runSmall(kDemo, out);
    expectInputError(refused, {"--out", out.string(), "--overwrite"});
    EXPECT_EQ(readText(out / "precious.txt"), "user data");
    EXPECT_FALSE(fs::exists(out / "report.json"));

    Result ok = runSmall(kDemo, out, {"--overwrite"});
    ASSERT_EQ(ok.code, 0) << ok.describe();
    EXPECT_EQ(readText(out / "precious.txt"), "user data");
    EXPECT_TRUE(fs::is_regular_file(out / "report.json"));

    // --out naming a file.
    Result file = runSmall(kDemo, out / "precious.txt");
    expectInputError(file, {"--out", "not a directory"});
    EXPECT_EQ(readText(out / "precious.txt"), "user data");
}

// --- exit code 1: valid input, failure while running ------------------------------------------

TEST(CliRun, RuntimeFailureExitsWithOne) {
    TempDir tmp;
    Result r = runSmall(kDemo, tmp / "out", {"--device", "no-such-gpu-anywhere"});
    EXPECT_EQ(r.code, 1) << r.describe();
    EXPECT_TRUE(contains(r.err, "error:")) << r.describe();
    EXPECT_TRUE(contains(r.err, "no-such-gpu-anywhere")) << r.describe();
    EXPECT_FALSE(fs::exists(tmp / "out" / "report.json"));
}

// --- exit code 2: bad input, errors name the flag or file -------------------------------------
// None of these reaches the GPU: every check runs before the device is created.

TEST(CliInput, BadSet) {
    TempDir tmp;
    const std::string out = (tmp / "out").string();
    auto run = [&](const std::string& set) {
        return cli({"run", kDemo.string(), "--out", out, "--size", "8x8", "--set", set});
    };
    expectInputError(run("nosuch.value=1"), {"--set nosuch.value=1", "no pass 'nosuch'"});
    expectInputError(run("nose.value=1"), {"--set nose.value=1", "did you mean 'noise'"});
    expectInputError(run("noise.valeu=1"),
                     {"--set noise.valeu=1", "no parameter 'valeu'", "did you mean 'value'"});
    expectInputError(run("noise.seed=abc"), {"--set noise.seed=abc"});
    expectInputError(run("noise.seed=1.5"), {"--set noise.seed=1.5"});
    expectInputError(run("noise.seed=-3"), {"--set noise.seed=-3"});  // range 0..2^31-1
    expectInputError(run("noise.animate=3"), {"--set noise.animate=3"});
    expectInputError(run("noise.value=[1,2]"), {"--set noise.value=[1,2]"});
    expectInputError(run("noise.pattern=plaid"), {"--set noise.pattern=plaid", "plaid"});
    expectInputError(run("tm.exposure=\"2\""), {"--set tm.exposure=\"2\""});
    expectInputError(run("noisevalue"), {"--set noisevalue", "pass.param=value"});
    expectInputError(run("noise.value"), {"--set noise.value", "pass.param=value"});
    EXPECT_FALSE(fs::exists(out));
}

TEST(CliInput, BadSize) {
    TempDir tmp;
    const std::string out = (tmp / "out").string();
    for (const std::string size : {"32", "32x", "x32", "0x32", "32x0", "20000x32", "-1x32",
                                   "32x32x1", "abc", "32X32", " 32x32"}) {
        Result r = cli({"run", kDemo.string(), "--out", out, "--size", size});
        expectInputError(r, {"--size"});
    }
    // validate reads --size too.
    expectInputError(cli({"validate", kDemo.string(), "--size", "1x99999"}), {"--size"});
    EXPECT_FALSE(fs::exists(out));
}

TEST(CliInput, BadSaveFrames) {
    TempDir tmp;
    const std::string out = (tmp / "out").string();
    for (const std::string frames : {"5", "2", "0,9", "first", "1,,0", "-1", "1;0", ""}) {
        Result r = cli({"run", kDemo.string(), "--out", out, "--size", "8x8", "--frames", "2",
                        "--save-frames", frames});
        expectInputError(r, {"--save-frames"});
    }
    EXPECT_FALSE(fs::exists(out));
}

TEST(CliInput, BadFramesSeedScene) {
    TempDir tmp;
    const std::string out = (tmp / "out").string();
    auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = {"run", kDemo.string(), "--out", out, "--size", "8x8"};
        args.insert(args.end(), extra.begin(), extra.end());
        return cli(args);
    };
    for (const std::string frames : {"0", "-1", "abc", "1.5", "99999999999999"})
        expectInputError(run({"--frames", frames}), {"--frames"});
    for (const std::string seed : {"-1", "-7", "abc", "1.5"})
        expectInputError(run({"--seed", seed}), {"--seed"});
    expectInputError(run({"--scene", "atlantis"}), {"--scene", "atlantis"});
    EXPECT_FALSE(fs::exists(out));
}

TEST(CliInput, MissingGraphFile) {
    TempDir tmp;
    const fs::path missing = tmp / "no_such_graph.json";
    expectInputError(cli({"run", missing.string(), "--out", (tmp / "out").string()}),
                     {missing.string(), "cannot read file"});
    expectInputError(cli({"validate", missing.string()}), {missing.string(), "cannot read"});
    EXPECT_FALSE(fs::exists(tmp / "out"));
}

TEST(CliInput, BadJson) {
    TempDir tmp;
    const fs::path bad = tmp / "broken.json";
    writeText(bad, "{\n  \"version\": 1,\n  \"passes\": [ , ]\n}\n");
    expectInputError(cli({"run", bad.string(), "--out", (tmp / "out").string()}),
                     {bad.string(), "line 3", "JSON syntax error"});
    expectInputError(cli({"validate", bad.string()}), {bad.string(), "line 3"});

    // Valid JSON, invalid graph: the compile error names the file and the JSON pointer.
    const fs::path badPass = tmp / "bad_pass.json";
    writeText(badPass, R"({"version": 1, "passes": [{"name": "src", "type": "ImageSorce"}],
                           "outputs": ["src.color"]})");
    expectInputError(cli({"validate", badPass.string()}),
                     {badPass.string(), "/passes/0", "ImageSource"});
    expectInputError(cli({"run", badPass.string(), "--out", (tmp / "out").string()}),
                     {badPass.string(), "/passes/0"});
    EXPECT_FALSE(fs::exists(tmp / "out"));
}

TEST(CliInput, UsageErrors) {
    expectInputError(cli({}), {});
    expectInputError(cli({"frobnicate"}), {"subcommand"});
    expectInputError(cli({"run"}), {"graph"});
    expectInputError(cli({"run", kDemo.string(), "--bogus"}), {"--bogus"});
    expectInputError(cli({"validate"}), {"graph"});
    expectInputError(cli({"passes", "--bogus"}), {"--bogus"});
    expectInputError(cli({"passes", "Tonemapp"}), {"Tonemapp", "did you mean 'Tonemap'"});
}

// --- help and version -------------------------------------------------------------------------

TEST(CliHelp, EverySubcommandHasHelp) {
    for (std::vector<std::string> args : {std::vector<std::string>{"--help"},
                                          {"-h"},
                                          {"run", "--help"},
                                          {"validate", "--help"},
                                          {"passes", "--help"},
                                          {"bench", "--help"}}) {
        Result r = cli(args);
        EXPECT_EQ(r.code, 0) << r.describe();
        EXPECT_TRUE(contains(r.out, "Usage") || contains(r.out, "usage")) << r.describe();
    }
    Result run = cli({"run", "--help"});
    for (const char* flag :
         {"--out", "--frames", "--size", "--set", "--seed", "--save-frames", "--overwrite",
          "--device", "--validation", "--reference", "--reference-output"})
        EXPECT_TRUE(contains(run.out, flag)) << flag << "\n" << run.out;
    Result top = cli({"--help"});
    for (const char* sub : {"run", "validate", "passes"})
        EXPECT_TRUE(contains(top.out, sub)) << sub << "\n" << top.out;

    Result version = cli({"--version"});
    EXPECT_EQ(version.code, 0) << version.describe();
    EXPECT_FALSE(version.out.empty()) << version.describe();
}

// --- validate ---------------------------------------------------------------------------------

TEST(CliValidate, EveryShippedGraphIsValid) {
    std::vector<fs::path> graphs;
    // graphs/cameras/ holds camera paths and graphs/benches/ bench files, not graphs (tested by
    // CameraPathTests and CliBenchTests).
    for (const auto& e : fs::recursive_directory_iterator(kRepo / "graphs"))
        if (e.is_regular_file() && e.path().extension() == ".json" &&
            e.path().parent_path().filename() != "cameras" &&
            e.path().parent_path().filename() != "benches")
            graphs.push_back(e.path());
    std::sort(graphs.begin(), graphs.end());
    ASSERT_GE(graphs.size(), 5u) << "graphs/ should hold demo.json and graphs/tests/*.json";
    for (const auto& g : graphs) {
        Result r = cli({"validate", g.string()});
        EXPECT_EQ(r.code, 0) << r.describe();
        EXPECT_TRUE(contains(r.out, g.string() + ": ok")) << r.describe();
    }
}

TEST(CliValidate, DumpJsonParses) {
    Result r = cli({"validate", kDemo.string(), "--dump", "--json", "--size", "32x32"});
    ASSERT_EQ(r.code, 0) << r.describe();
    json dump = json::parse(r.out, nullptr, false);
    ASSERT_FALSE(dump.is_discarded()) << r.out;
    EXPECT_EQ(dump.at("size"), json::array({32, 32}));
    EXPECT_EQ(dump.at("order").size(), 4u) << dump["order"];
    ASSERT_TRUE(dump.at("passes").is_array());
    EXPECT_EQ(dump["passes"].size(), 4u);
    for (const auto& p : dump["passes"]) EXPECT_TRUE(p.at("alive").get<bool>()) << p;
    ASSERT_TRUE(dump.at("resources").is_array());
    EXPECT_FALSE(dump["resources"].empty());
    const json& memory = dump.at("memory");
    EXPECT_TRUE(memory.at("transient_bytes").is_number_unsigned());
    EXPECT_TRUE(memory.at("persistent_bytes").is_number_unsigned());

    Result text = cli({"validate", kDemo.string(), "--dump"});
    ASSERT_EQ(text.code, 0) << text.describe();
    EXPECT_FALSE(text.out.empty());
    EXPECT_TRUE(json::parse(text.out, nullptr, false).is_discarded()) << "--dump alone is text";
}

// --- passes -----------------------------------------------------------------------------------

// docs/passes/<Type>.md holds the field and parameter tables generated from the registry: every
// registered type has a page and no page has drifted from the code.
TEST(CliPasses, DocPagesAreCurrentForEveryPassType) {
    Result r = cli({"passes", "--check-docs", (kRepo / "docs" / "passes").string()});
    EXPECT_EQ(r.code, 0) << r.describe() << "\nrun: build/fovea passes --update-docs docs/passes";
}

TEST(CliPasses, CheckDocsCatchesDriftAndUpdateDocsRepairsIt) {
    TempDir dir;
    for (const auto& entry : fs::directory_iterator(kRepo / "docs" / "passes"))
        fs::copy_file(entry.path(), dir.path() / entry.path().filename());
    // A hand edit inside a generated table is drift.
    const fs::path taa = dir.path() / "TAA.md";
    std::string text = readText(taa);
    const std::string row = "| `alpha` | float | `0.1` |";
    const size_t at = text.find(row);
    ASSERT_NE(at, std::string::npos) << text;
    text.replace(at, row.size(), "| `alpha` | float | `0.2` |");
    writeText(taa, text);
    Result stale = cli({"passes", "--check-docs", dir.path().string()});
    EXPECT_EQ(stale.code, 1) << stale.describe();
    EXPECT_NE(stale.err.find("TAA.md"), std::string::npos) << stale.describe();
    Result update = cli({"passes", "--update-docs", dir.path().string()});
    EXPECT_EQ(update.code, 0) << update.describe();
    EXPECT_EQ(readText(taa), readText(kRepo / "docs" / "passes" / "TAA.md"));
    // A page without the markers, and a missing page, are named.
    writeText(dir.path() / "Blit.md", "# Blit\n\nno tables\n");
    fs::remove(dir.path() / "Tonemap.md");
    Result broken = cli({"passes", "--check-docs", dir.path().string()});
    EXPECT_EQ(broken.code, 1) << broken.describe();
    EXPECT_NE(broken.err.find("Blit.md"), std::string::npos) << broken.describe();
    EXPECT_NE(broken.err.find("missing the marker pair"), std::string::npos) << broken.describe();
    EXPECT_NE(broken.err.find("Tonemap.md: missing"), std::string::npos) << broken.describe();
}

// The Koskela pipeline wires no history edge: TAA's and BMFR's histories are pass-declared, and
// the dump shows them with their memory.
TEST(CliValidate, DumpShowsPassDeclaredHistory) {
    Result r = cli({"validate", (kRepo / "graphs" / "koskela_bmfr.json").string(), "--dump",
                    "--size", "64x64"});
    ASSERT_EQ(r.code, 0) << r.describe();
    EXPECT_NE(r.out.find("taa.result  64x64 rgba32f  history ring 2 (pass keeps 1 previous frame)"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("bmfr.hist_accum  64x64 rgba32f  history ring 2"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("bmfr.coefficients  buffer 3456 B"), std::string::npos) << r.out;
    EXPECT_EQ(readText(kRepo / "graphs" / "koskela_bmfr.json").find("taa.history"),
              std::string::npos);
}

TEST(CliPasses, MarkdownShowsDeclaredHistoryAndBufferRules) {
    Result r = cli({"passes", "BMFR", "--markdown"});
    ASSERT_EQ(r.code, 0) << r.describe();
    EXPECT_NE(r.out.find("`hist_accum` | internal, keeps 1 previous frame (`prev_hist_accum`)"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("0 B + 384 B per 32x32 block (+1 per axis)"), std::string::npos) << r.out;
}

TEST(CliPasses, JsonListsTheUtilityPasses) {
    Result r = cli({"passes", "--json"});
    ASSERT_EQ(r.code, 0) << r.describe();
    json all = json::parse(r.out, nullptr, false);
    ASSERT_FALSE(all.is_discarded()) << r.out;
    ASSERT_TRUE(all.is_array());
    std::map<std::string, json> byType;
    for (const auto& p : all) {
        ASSERT_TRUE(p.at("type").is_string()) << p;
        EXPECT_TRUE(p.at("doc").is_string()) << p;
        EXPECT_TRUE(p.at("fields").is_array()) << p;
        EXPECT_TRUE(p.at("params").is_array()) << p;
        byType[p["type"]] = p;
    }
    // Other pass types may be registered too; the five utility passes always are.
    const std::map<std::string, std::set<std::string>> kUtility = {
        {"Accumulate", {"maxFrames"}},
        {"Blit", {"scale", "format", "filter", "activeEvery"}},
        {"Combine", {"weightA", "weightB", "absolute"}},
        {"ImageSource", {"pattern", "value", "seed", "animate"}},
        {"Tonemap", {"exposure", "operator", "srgb"}},
    };
    for (const auto& [type, params] : kUtility) {
        ASSERT_TRUE(byType.count(type)) << type << " missing from passes --json";
        const json& p = byType[type];
        EXPECT_FALSE(p["doc"].get<std::string>().empty()) << type;
        EXPECT_FALSE(p["fields"].empty()) << type;
        std::set<std::string> names;
        for (const auto& q : p["params"]) {
            ASSERT_TRUE(q.at("name").is_string()) << type << q;
            EXPECT_TRUE(q.at("type").is_string()) << type << q;
            EXPECT_TRUE(q.contains("default")) << type << q;
            EXPECT_TRUE(q.at("doc").is_string()) << type << q;
            names.insert(q["name"]);
        }
        for (const auto& name : params)
            EXPECT_TRUE(names.count(name)) << type << " lacks parameter " << name;
        for (const auto& f : p["fields"]) {
            EXPECT_TRUE(f.at("name").is_string()) << type << f;
            EXPECT_TRUE(f.at("kind").is_string()) << type << f;
            EXPECT_TRUE(f.at("format").is_string()) << type << f;
        }
    }

    // One type only, and the text listing.
    Result one = cli({"passes", "Tonemap", "--json"});
    ASSERT_EQ(one.code, 0) << one.describe();
    json onlyTonemap = json::parse(one.out);
    ASSERT_EQ(onlyTonemap.size(), 1u);
    EXPECT_EQ(onlyTonemap[0]["type"], "Tonemap");
    Result text = cli({"passes"});
    ASSERT_EQ(text.code, 0) << text.describe();
    for (const auto& [type, params] : kUtility) EXPECT_TRUE(contains(text.out, type)) << type;
}

// --- fixes: unknown subcommand, --save-frames trailing comma, validate = run for bypass pairs,
// PNG of an rgba8 output written as-is ------------------------------------------------------

TEST(CliFixes, UnknownSubcommandIsNamed) {
    expectInputError(cli({"frobnicate"}), {"unknown subcommand 'frobnicate'", "run", "validate"});
    expectInputError(cli({"valdate", kDemo.string()}),
                     {"unknown subcommand 'valdate'", "did you mean 'validate'"});
    // Known subcommands keep their own errors.
    expectInputError(cli({"run"}), {"graph"});
    EXPECT_FALSE(contains(cli({"run"}).err, "unknown subcommand"));
}

TEST(CliFixes, SaveFramesTrailingOrLeadingCommaIsRejected) {
    // An empty item, also a trailing one (std::getline drops it), is an error.
    TempDir tmp;
    const std::string out = (tmp / "out").string();
    for (const std::string frames : {"0,", "1,0,", ",0", ","}) {
        Result r = cli({"run", kDemo.string(), "--out", out, "--size", "8x8", "--frames", "2",
                        "--save-frames", frames});
        expectInputError(r, {"--save-frames", "'" + frames + "'"});
    }
    EXPECT_FALSE(fs::exists(out));
}

TEST(CliFixes, ValidateRejectsABypassSizeMismatchLikeRun) {
    const fs::path bad =
        kRepo / "tests" / "graph" / "bad" / "compile" / "bypass_size_mismatch.json";
    const std::string message =
        bad.string() +
        ": /passes/1: pass 'b' bypasses 'color' into 'result' but they differ in "
        "size or format";
    Result v = cli({"validate", bad.string()});
    expectInputError(v, {message});
    EXPECT_FALSE(contains(v.out, "ok")) << v.describe();
    TempDir tmp;
    expectInputError(cli({"run", bad.string(), "--out", (tmp / "out").string()}), {message});
}

TEST(CliFixes, PngOfAnRgba8OutputHoldsItsBytes) {
    // Needs `fovea run` to write 8-bit UNORM outputs with image::PngEncoding::AsIs
    // (apps/fovea/RunCommand.cpp): the PNG of tm.ldr then equals its EXR * 255 exactly.
    TempDir tmp;
    const fs::path out = tmp / "out";
    Result r = runSmall(kDemo, out);
    ASSERT_EQ(r.code, 0) << r.describe();
    std::vector<float> exr = pixels(out / "tm.ldr.frame0001.exr");
    std::vector<float> png = pixels(out / "tm.ldr.frame0001.png");  // read back as k / 255
    ASSERT_EQ(exr.size(), png.size());
    ASSERT_FALSE(exr.empty());
    size_t differ = 0;
    for (size_t i = 0; i < exr.size(); ++i)
        differ += std::lround(exr[i] * 255.0f) != std::lround(png[i] * 255.0f);
    EXPECT_EQ(differ, 0u) << "the PNG of an rgba8 output was encoded again";
}
