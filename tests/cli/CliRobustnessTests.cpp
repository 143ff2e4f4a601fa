// A new user's first hour (issue 16): each robustness finding reproduced against the `fovea`
// executable. Deeply nested JSON, numbers beyond double, empty or NaN flag values, graph names
// that would leave out/, concurrent runs on one folder, failed writes, Ctrl-C, scene overrides
// that kept the wrong camera, warnings `validate` did not print, and megabyte error lines.
// Most checks stop before the device; the GPU runs are 16x16 or 32x32, a few frames.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>

#include <chrono>
#include <thread>

#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

const fs::path kBmfrGraph = kRepo / "graphs" / "koskela_bmfr.json";

// A valid one-pass graph whose `extra` text is spliced into the top-level object.
std::string graphWith(const std::string& extra, const std::string& name = "tiny") {
    return R"({"version": 1, "name": ")" + name +
           R"(", "passes": [{"name": "src", "type": "ImageSource"}],
               "outputs": ["src.color"])" +
           (extra.empty() ? "" : ", " + extra) + "}";
}

std::string nested(const std::string& key, size_t depth) {
    std::string text;
    text.reserve(depth * (key.size() + 5));
    for (size_t i = 0; i < depth; ++i) text += "{\"" + key + "\": ";
    text += "1";
    text.append(depth, '}');
    return text;
}

bool anyPartialFile(const fs::path& dir) {
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().rfind(".partial.", 0) == 0) return true;
    return false;
}

}  // namespace

// --- 1. deep nesting: SIGSEGV before, exit 2 naming the file now -------------------------------

TEST(CliInputRobustness, DeeplyNestedGraphParamsAndEditorAreRefused) {
    TempDir tmp;
    const fs::path params = tmp / "params.json";
    writeText(params, R"({"version": 1, "passes": [{"name": "src", "type": "ImageSource",
        "params": )" + nested("a", 70000) +
                          R"(}], "outputs": ["src.color"]})");
    Result r = cli({"validate", params.string()});
    expectInputError(r, {params.string(), "nested deeper than 256"});
    EXPECT_LT(r.err.size(), 4000u) << "the pointer of a 70,000-deep value must be cut";

    const fs::path editor = tmp / "editor.json";
    writeText(editor, graphWith("\"editor\": " + nested("e", 70000)));
    expectInputError(cli({"validate", editor.string()}),
                     {editor.string(), "/editor/e/e", "nested deeper than 256"});

    // 200 levels are fine (the limit is far above any real graph).
    const fs::path fine = tmp / "fine.json";
    writeText(fine, graphWith("\"editor\": " + nested("e", 200)));
    Result ok = cli({"validate", fine.string()});
    EXPECT_EQ(ok.code, 0) << ok.describe();
}

TEST(CliInputRobustness, DeeplyNestedGltfExtrasAreRefused) {
    TempDir tmp;
    const fs::path gltf = tmp / "deep.gltf";
    writeText(gltf, R"({"asset": {"version": "2.0"}, "extras": )" + nested("x", 20000) +
                        R"(, "extensions": {}})");
    const fs::path graph = tmp / "g.json";
    writeText(graph, graphWith(""));
    expectInputError(cli({"validate", graph.string(), "--scene", gltf.string()}),
                     {"--scene", gltf.string(), "/extras/x/x", "nested deeper than 256"});
}

// --- 4. 1e400: exit 2 naming the file and the pointer -------------------------------------------

TEST(CliInputRobustness, NumberBeyondDoubleNamesFileAndPointer) {
    TempDir tmp;
    const fs::path graph = tmp / "big.json";
    writeText(graph, R"({"version": 1, "passes": [{"name": "src", "type": "ImageSource",
        "params": {"value": [1, 1e400, 1]}}], "outputs": ["src.color"]})");
    expectInputError(cli({"validate", graph.string()}),
                     {graph.string(), "/passes/0/params/value/1", "1e400"});

    const fs::path camera = tmp / "cam.json";
    writeText(camera, R"({"version": 1, "keyframes": [{"frame": 0, "position": [0, 1e400, 0],
        "target": [0, 0, 0]}]})");
    const fs::path valid = tmp / "valid.json";
    writeText(valid, graphWith(""));
    expectInputError(cli({"validate", valid.string(), "--scene", "builtin:cornell", "--camera",
                          camera.string()}),
                     {camera.string(), "/keyframes/0/position/1"});
}

TEST(CliInputRobustness, CameraErrorReachedThroughTheGraphNamesTheGraph) {
    TempDir tmp;
    const fs::path camera = tmp / "cam.json";
    writeText(camera, R"({"version": 1, "keyframes": [{"frame": 0, "position": [0, 0, 1e999]}]})");
    const fs::path graph = tmp / "g.json";
    writeText(graph,
              graphWith(R"("defaults": {"scene": "builtin:cornell", "camera": "cam.json"})"));
    expectInputError(cli({"validate", graph.string()}),
                     {graph.string(), "/defaults/camera", camera.string(), "/keyframes/0"});
}

// --- 5. silent acceptances: exit 2 naming the flag -----------------------------------------------

TEST(CliInputRobustness, EmptyNanAndOutOfRangeFlagValuesAreRefused) {
    TempDir tmp;
    const std::string out = (tmp / "out").string();
    const std::string demo = kDemo.string();
    auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = {"run", demo, "--out", out, "--size", "8x8"};
        args.insert(args.end(), extra.begin(), extra.end());
        return cli(args);
    };
    expectInputError(run({"--ipd", "nan"}), {"--ipd"});
    expectInputError(run({"--ipd", "inf"}), {"--ipd"});
    expectInputError(run({"--seed", "9223372036854775808"}), {"--seed"});
    expectInputError(run({"--seed", "99999999999999999999999"}), {"--seed"});
    expectInputError(cli({"run", demo, "--out", out, "--size", ""}), {"--size", "empty"});
    expectInputError(run({"--gaze", ""}), {"--gaze", "empty"});
    expectInputError(cli({"run", demo, "--out", ""}), {"--out", "empty"});
    expectInputError(run({"--camera", ""}), {"--camera", "empty"});
    expectInputError(run({"--device", ""}), {"--device", "empty"});
    expectInputError(run({"--scene", ""}), {"--scene", "empty"});
    expectInputError(cli({"validate", demo, "--size", ""}), {"--size", "empty"});
    EXPECT_FALSE(fs::exists(out)) << "nothing may be written for refused input";

    // One eye of width 1/2 = 0 pixels.
    expectInputError(cli({"validate", kPathTraceGraph.string(), "--scene", "builtin:cornell",
                          "--stereo", "--size", "1x16"}),
                     {"--size", "stereo", "at least 2"});
    Result two = cli({"validate", kPathTraceGraph.string(), "--scene", "builtin:cornell",
                      "--stereo", "--size", "2x16"});
    EXPECT_EQ(two.code, 0) << two.describe();

    // The largest seed still works (it is accepted, not clamped from something larger).
    Result big = cli({"run", demo, "--out", out, "--size", "8x8", "--frames", "1", "--seed",
                      "9223372036854775807", "--quiet"});
    ASSERT_EQ(big.code, 0) << big.describe();
    EXPECT_EQ(json::parse(readText(fs::path(out) / "report.json"))["seed"],
              uint64_t(9223372036854775807ull));

    // compare --peak nan names the flag (before: the metric code's message, no flag).
    const fs::path exr = fs::path(out) / "tm.ldr.exr";
    expectInputError(cli({"compare", exr.string(), exr.string(), "--peak", "nan"}), {"--peak"});
    expectInputError(cli({"compare", exr.string(), exr.string(), "--epsilon", "nan"}),
                     {"--epsilon"});
}

// README said `--frames 0` means the default; the CLI refuses it. They agree now: refused.
TEST(CliInputRobustness, FramesZeroIsRefusedAsTheReadmeSays) {
    TempDir tmp;
    expectInputError(cli({"run", kDemo.string(), "--out", (tmp / "o").string(), "--frames", "0"}),
                     {"--frames"});
    const std::string readme = readText(kRepo / "README.md");
    EXPECT_FALSE(contains(readme, "`0` also means the default"));
}

// --- 8. echoed values are cut; validate prints the scene warnings -------------------------------

TEST(CliInputRobustness, ErrorLinesCutLongQuotedValues) {
    TempDir tmp;
    const fs::path graph = tmp / "long.json";
    const std::string type(1 << 20, 'Q');  // a 1 MB pass type
    writeText(graph, R"({"version": 1, "passes": [{"name": "src", "type": ")" + type +
                         R"("}], "outputs": ["src.color"]})");
    Result r = cli({"validate", graph.string()});
    expectInputError(r, {graph.string(), "/passes/0/type", "\u2026"});
    EXPECT_LT(r.err.size(), 4000u) << "a 1 MB value echoed in full";
}

TEST(CliInputRobustness, ValidatePrintsTheSceneWarningsOfRun) {
    // koskela_bmfr's defaults.camera is a path for builtin:cornell; another scene drops it with a
    // warning (it would render black), and validate prints it as run does.
    Result r = cli({"validate", kBmfrGraph.string(), "--scene", "builtin:forest"});
    ASSERT_EQ(r.code, 0) << r.describe();
    EXPECT_TRUE(contains(r.err, "warning:")) << r.describe();
    EXPECT_TRUE(contains(r.err, "defaults.camera")) << r.describe();
    EXPECT_TRUE(contains(r.err, "--camera frame")) << r.describe();

    // The same scene as the graph's default keeps the camera: no such warning.
    Result same = cli({"validate", kBmfrGraph.string(), "--scene", "builtin:cornell"});
    ASSERT_EQ(same.code, 0) << same.describe();
    EXPECT_FALSE(contains(same.err, "defaults.camera")) << same.describe();
}

// --- 7. the graph's name never leaves out/ -------------------------------------------------------

TEST(CliRunRobustness, GraphNameCannotEscapeTheOutFolder) {
    TempDir tmp;
    const fs::path work = tmp / "work";
    fs::create_directories(work);
    const fs::path absTarget = tmp / "abs_target";
    for (const std::string& name : {std::string("../escaped"), absTarget.string()}) {
        const fs::path graph = tmp / "named.json";
        writeText(graph, graphWith("", name));
        const std::string line = "cd " + shellQuote(work.string()) + " && " +
                                 shellQuote(FOVEA_EXE) + " run " + shellQuote(graph.string()) +
                                 " --size 8x8 --quiet --overwrite >/dev/null 2>&1";
        EXPECT_EQ(std::system(line.c_str()), 0) << name;
    }
    EXPECT_FALSE(fs::exists(tmp / "escaped")) << "'../escaped' left work/out";
    EXPECT_FALSE(fs::exists(absTarget)) << "an absolute name left work/out";
    EXPECT_TRUE(fs::exists(work / "out" / "_escaped" / "report.json"));
}

// --- 2. writes: checked, atomic, report.json last with "finished" --------------------------------

TEST(CliRunRobustness, ReportSaysFinishedAndNoPartialFilesRemain) {
    TempDir tmp;
    Result r = runSmall(kDemo, tmp / "out");
    ASSERT_EQ(r.code, 0) << r.describe();
    json report = json::parse(readText(tmp / "out" / "report.json"));
    EXPECT_EQ(report.at("finished"), true);
    EXPECT_EQ(report.at("frames_run"), 2);
    EXPECT_FALSE(anyPartialFile(tmp / "out"));
    EXPECT_FALSE(fs::exists(tmp / "out" / ".fovea.lock"));
}

TEST(CliRunRobustness, FailedWritesExitOneAndLeaveNoReport) {
    TempDir tmp;
    const fs::path out = tmp / "out";
    fs::create_directories(out);
    // A previous run's report: with --overwrite it must not survive beside the new images.
    writeText(out / "report.json", R"({"finished": true})");
    // A directory where the PNG's temporary file goes: the write fails like a full disk would.
    fs::create_directories(out / ".partial.tm.ldr.frame0001.png");
    Result png = runSmall(kDemo, out, {"--overwrite"});
    EXPECT_EQ(png.code, 1) << png.describe();
    EXPECT_TRUE(contains(png.err, "tm.ldr.frame0001.png")) << png.describe();
    EXPECT_FALSE(fs::exists(out / "report.json")) << "an old report beside a failed run";
    EXPECT_FALSE(fs::exists(out / "tm.ldr.frame0001.png"));
    fs::remove_all(out / ".partial.tm.ldr.frame0001.png");

    fs::create_directories(out / ".partial.report.json");
    Result report = runSmall(kDemo, out, {"--overwrite"});
    EXPECT_EQ(report.code, 1) << report.describe();
    EXPECT_TRUE(contains(report.err, "report.json")) << report.describe();
    EXPECT_FALSE(fs::exists(out / "report.json"));
}

// --- 3. one run per folder -----------------------------------------------------------------------

TEST(CliRunRobustness, TwoRunsOnOneFolderCannotBothSucceed) {
    TempDir tmp;
    const fs::path out = tmp / "out";
    auto command = [&](int i) {
        return "( " + shellQuote(FOVEA_EXE) + " run " + shellQuote(kDemo.string()) + " --out " +
               shellQuote(out.string()) + " --size 16x16 --frames 8 --quiet >" +
               shellQuote((tmp / ("err" + std::to_string(i))).string()) + " 2>&1; echo $? >" +
               shellQuote((tmp / ("code" + std::to_string(i))).string()) + " )";
    };
    const std::string line = command(0) + " & " + command(1) + " & wait";
    ASSERT_EQ(std::system(line.c_str()), 0);
    const int a = std::stoi(readText(tmp / "code0")), b = std::stoi(readText(tmp / "code1"));
    EXPECT_EQ(std::min(a, b), 0) << readText(tmp / "err0") << readText(tmp / "err1");
    EXPECT_EQ(std::max(a, b), 2) << readText(tmp / "err0") << readText(tmp / "err1");
    EXPECT_TRUE(contains(readText(tmp / (a == 2 ? "err0" : "err1")), "--out"));

    // A folder locked by a live run is refused even with --overwrite.
    const int fd = ::open((out / ".fovea.lock").c_str(), O_RDWR | O_CREAT, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
    expectInputError(runSmall(kDemo, out, {"--overwrite"}), {"--out", "another fovea run"});
    ::close(fd);
}

// --- 2. Ctrl-C: report.json says "finished": false
// ------------------------------------------------

TEST(CliRunRobustness, InterruptLeavesAnUnfinishedReport) {
    TempDir tmp;
    const fs::path out = tmp / "out";
    const fs::path err = tmp / "stderr";
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        const int fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(fd, 2);
        ::execl(FOVEA_EXE, FOVEA_EXE, "run", kDemo.c_str(), "--out", out.c_str(), "--size", "16x16",
                "--frames", "100000", "--save-frames", "all", "--quiet",
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    // Wait for the second frame's files, then Ctrl-C.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(out / "tm.ldr.frame0001.png") && std::chrono::steady_clock::now() < deadline)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ::kill(child, SIGINT);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
    EXPECT_EQ(WEXITSTATUS(status), 1) << readText(err);
    EXPECT_TRUE(contains(readText(err), "interrupted")) << readText(err);
    ASSERT_TRUE(fs::exists(out / "report.json")) << readText(err);
    json report = json::parse(readText(out / "report.json"));
    EXPECT_EQ(report.at("finished"), false);
    EXPECT_LT(report.at("frames_run").get<int>(), 100000);
    EXPECT_GE(report.at("frames_run").get<int>(), 2);
    EXPECT_FALSE(anyPartialFile(out));
}

// --- any graph on any scene
// ------------------------------------------------------------------------

TEST(CliRunRobustness, CameraFrameFramesTheScene) {
    TempDir tmp;
    Result r = cli({"run", kPathTraceGraph.string(), "--out", (tmp / "out").string(), "--size",
                    "16x16", "--frames", "1", "--scene", "builtin:forest", "--camera", "frame"});
    ASSERT_EQ(r.code, 0) << r.describe();
    EXPECT_FALSE(contains(r.err, "black in every pixel")) << r.describe();
    json report = json::parse(readText(tmp / "out" / "report.json"));
    EXPECT_EQ(report.at("scene").at("camera"), "default");
}

// --- a lighter first run: `make demo` builds the executable only ---------------------------------

TEST(CliDemo, MakeDemoBuildsOnlyTheExecutable) {
    // -n prints the recipe without running it (dependencies' recipes too: deps, configure).
    TempDir tmp;
    const std::string line = "make -n -C " + shellQuote(kRepo.string()) +
                             " demo BUILD=" + shellQuote((tmp / "b").string()) + " >" +
                             shellQuote((tmp / "plan").string()) + " 2>&1";
    ASSERT_EQ(std::system(line.c_str()), 0) << readText(tmp / "plan");
    const std::string plan = readText(tmp / "plan");
    EXPECT_TRUE(contains(plan, "--target fovea")) << plan;
    for (std::istringstream lines(plan); !lines.eof();) {
        std::string l;
        std::getline(lines, l);
        if (contains(l, "cmake --build")) {
            EXPECT_TRUE(contains(l, "--target fovea")) << "builds more than the demo needs: " << l;
        }
    }
    EXPECT_TRUE(contains(plan, "out/demo")) << "prints where the pictures are";
    EXPECT_TRUE(contains(plan, "next:")) << "suggests one next command";
}

// A camera that looks away from the scene gave an all-black image with exit 0 and no word.
TEST(CliRunRobustness, AllBlackOutputIsWarned) {
    TempDir tmp;
    const fs::path camera = tmp / "away.json";
    writeText(camera, R"({"version": 1, "keyframes": [{"frame": 0, "position": [278, 273, -800],
        "target": [278, 273, -2000]}]})");
    Result r =
        cli({"run", kPathTraceGraph.string(), "--out", (tmp / "out").string(), "--size", "16x16",
             "--frames", "1", "--scene", "builtin:cornell", "--camera", camera.string()});
    ASSERT_EQ(r.code, 0) << r.describe();
    EXPECT_TRUE(contains(r.err, "black in every pixel")) << r.describe();
    json report = json::parse(readText(tmp / "out" / "report.json"));
    ASSERT_TRUE(report.at("warnings").is_array());
    ASSERT_FALSE(report["warnings"].empty());
    EXPECT_TRUE(contains(report["warnings"][0].get<std::string>(), "black in every pixel"));

    // Cornell's own camera: no such warning.
    Result framed = cli({"run", kPathTraceGraph.string(), "--out", (tmp / "own").string(), "--size",
                         "16x16", "--frames", "1", "--scene", "builtin:cornell"});
    ASSERT_EQ(framed.code, 0) << framed.describe();
    EXPECT_FALSE(contains(framed.err, "black in every pixel")) << framed.describe();
}

TEST(CliInputRobustness, NonRegularFilesAreRefusedNotRead) {
    // Issue 33, class 1: /dev/zero, a FIFO or a link to one named as a graph, camera path,
    // reference or compared image used to hang (and the JSON readers grew without bound). Every
    // such file is now refused before it is opened: exit 2 naming it, at once.
    TempDir tmp;
    const fs::path fifo = tmp / "pipe.json";
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    const fs::path zeroLink = tmp / "zero.exr";
    fs::create_symlink("/dev/zero", zeroLink);
    for (const fs::path& bad : {fs::path("/dev/zero"), fifo, zeroLink}) {
        expectInputError(cli({"validate", bad.string()}), {bad.string(), "not a regular file"});
        expectInputError(cli({"run", bad.string(), "--frames", "1"}),
                         {bad.string(), "not a regular file"});
    }
    expectInputError(runSmall(kPathTraceGraph, tmp / "camera", {"--camera", fifo.string()}),
                     {fifo.string(), "not a regular file"});
    expectInputError(
        runSmall(kPathTraceGraph, tmp / "reference", {"--reference", zeroLink.string()}),
        {zeroLink.string(), "not a regular file"});
    expectInputError(cli({"compare", zeroLink.string(), "/dev/zero"}),
                     {zeroLink.string(), "not a regular file"});
    expectInputError(cli({"bench", fifo.string(), "--out", (tmp / "bench").string()}),
                     {fifo.string(), "not a regular file"});
}

TEST(CliRunRobustness, AFullDiskNamesTheImageAndLeavesNoPartOfIt) {
    // Issue 33, class 3: the PNG write goes to a link to /dev/full (ENOSPC on every write).
    // OpenImageIO's own output (fovea's image library then) reported success and a 0-byte PNG took
    // the final name; now the run exits 1 naming the final file, and neither it nor its partial
    // file remains.
    TempDir tmp;
    const fs::path out = tmp / "out";
    fs::create_directories(out);
    fs::create_symlink("/dev/full", out / ".partial.pt.radiance.png");
    Result r = cli({"run", kPathTraceGraph.string(), "--size", "16x16", "--frames", "1", "--out",
                    out.string(), "--overwrite", "--quiet"});
    EXPECT_EQ(r.code, 1) << r.describe();
    EXPECT_TRUE(contains(r.err, (out / "pt.radiance.png").string() + ": cannot write: No space"))
        << r.describe();
    EXPECT_FALSE(fs::exists(out / "pt.radiance.png"));
    EXPECT_FALSE(fs::is_symlink(out / ".partial.pt.radiance.png"));
}

TEST(CliRunRobustness, ARenderTooLargeForTheDeviceNamesImageBytesAndBudget) {
    // Issue 33, class 5: a 16384^2 render on lavapipe (2 GiB heap) ended in
    // "vk::Image::bindMemory: ErrorOutOfDeviceMemory" with no image and no amount, after the
    // validation layer had complained about the allocation. Now the size is checked against the
    // heap before Vulkan is asked: exit 1 naming the image, its bytes and the heap, no output
    // folder left behind.
    TempDir tmp;
    const fs::path out = tmp / "out";
    Result r = cli({"run", kPathTraceGraph.string(), "--size", "16384x16384", "--frames", "1",
                    "--out", out.string(), "--quiet"});
    if (r.code == 0) GTEST_SKIP() << "this device holds a 16384^2 render";
    EXPECT_EQ(r.code, 1) << r.describe();
    EXPECT_TRUE(contains(r.err, "(16384x16384)") || contains(r.err, "16384x16384 rgba"))
        << r.describe();
    EXPECT_TRUE(contains(r.err, "4294967296 bytes (4096 MiB)")) << r.describe();
    EXPECT_TRUE(contains(r.err, "memory heap") || contains(r.err, "largest image")) << r.describe();
    EXPECT_TRUE(contains(r.err, "render at a smaller --size")) << r.describe();
    EXPECT_FALSE(contains(r.err, "validation")) << r.describe();
    EXPECT_FALSE(fs::exists(out / "report.json"));
}

TEST(CliInputRobustness, UnusablePathsAreInputErrorsNamingTheFlag) {
    // Issue 33, class 5: a file name over 255 bytes or a loop of symbolic links used to end in
    // exit 1 "filesystem error: ..."; they are bad input: exit 2 naming the flag or the pointer.
    TempDir tmp;
    const std::string longName = (tmp / std::string(300, 'a')).string();
    const fs::path loop = tmp / "loop1";
    fs::create_symlink(tmp / "loop2", loop);
    fs::create_symlink(loop, tmp / "loop2");
    expectInputError(runSmall(kPathTraceGraph, longName), {"--out", "more than the 255"});
    expectInputError(runSmall(kPathTraceGraph, loop), {"--out", "a loop of symbolic links"});
    expectInputError(runSmall(kPathTraceGraph, tmp / "o", {"--reference", longName + ".exr"}),
                     {"--reference", "more than the 255"});
    expectInputError(cli({"compare", loop.string(), "b.exr"}),
                     {"test", "a loop of symbolic links"});
    const fs::path bench = tmp / "b.json";
    writeText(bench, R"({"version": 1, "scene": "builtin:cornell", "size": [8, 8], "frames": 2,
        "reference": ")" +
                         longName + R"(.exr", "graphs": [{"file": ")" + kPathTraceGraph.string() +
                         R"("}]})");
    expectInputError(cli({"bench", bench.string(), "--out", (tmp / "bo").string()}),
                     {bench.string(), "/reference", "more than the 255"});
}
