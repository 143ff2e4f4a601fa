// ImageFile (passes/ImageFile, docs/passes/ImageFile.md) through the executable: an EXR sequence
// written by `fovea run` read back exactly, channel selection, the shipped denoise graph, and
// exit-2 errors naming the file (wrong size, missing frame, unknown channel, bad pattern).
#include "core/util/Error.h"
#include "passes/ImageFile/ImageFilePass.h"
#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

const fs::path kDenoiseGraph = kRepo / "graphs" / "denoise_exr_sequence.json";

// Two frames of 1 spp path tracing of the Cornell box, 32x32: seq/pt.radiance.frame000{0,1}.exr.
fs::path writeSequence(const TempDir& tmp) {
    const fs::path seq = tmp / "seq";
    Result r = cli({"run", kPathTraceGraph.string(), "--out", seq.string(), "--size", "32x32",
                    "--frames", "2", "--save-frames", "all", "--quiet"});
    EXPECT_EQ(r.code, 0) << r.describe();
    return seq;
}

// A graph whose only output is the ImageFile pass's image.
fs::path copyGraph(const TempDir& tmp, const std::string& path, const std::string& channels) {
    const fs::path graph = tmp / "copy.json";
    writeText(graph, R"({"version": 1, "name": "copy", "passes": [{"name": "src",
        "type": "ImageFile", "params": {"path": ")" +
                         path + R"(", "channels": ")" + channels +
                         R"("}}], "outputs": ["src.color"]})");
    return graph;
}

}  // namespace

TEST(ImageFilePattern, FormatsOneIntegerConversion) {
    using fovea::passes::formatFramePattern;
    EXPECT_EQ(formatFramePattern("f%04d.exr", 7, "x"), "f0007.exr");
    EXPECT_EQ(formatFramePattern("f%d.exr", 12345, "x"), "f12345.exr");
    EXPECT_EQ(formatFramePattern("f%3d.exr", 5, "x"), "f  5.exr");
    EXPECT_EQ(formatFramePattern("100%%_%02d.png", 3, "x"), "100%_03.png");
    EXPECT_EQ(formatFramePattern("still.exr", 9, "x"), "still.exr");
    for (const char* bad : {"f%s.exr", "f%d_%d.exr", "f%", "f%x", "f%999999999999d"})
        EXPECT_THROW(formatFramePattern(bad, 1, "x"), fovea::InputError) << bad;
}

TEST(CliImageFile, ReadsASequenceExactlyAndSelectsChannels) {
    TempDir tmp;
    const fs::path seq = writeSequence(tmp);
    const std::string pattern = (seq / "pt.radiance.frame%04d.exr").string();

    Result r = cli({"run", copyGraph(tmp, pattern, "").string(), "--out", (tmp / "a").string(),
                    "--size", "32x32", "--frames", "2", "--save-frames", "all", "--quiet"});
    ASSERT_EQ(r.code, 0) << r.describe();
    for (const char* frame : {"frame0000", "frame0001"}) {
        const std::vector<float> in = pixels(seq / ("pt.radiance." + std::string(frame) + ".exr"));
        const std::vector<float> out =
            pixels(tmp / "a" / ("src.color." + std::string(frame) + ".exr"));
        EXPECT_EQ(in, out) << frame;
    }
    EXPECT_NE(pixels(seq / "pt.radiance.frame0000.exr"), pixels(seq / "pt.radiance.frame0001.exr"))
        << "the two frames must differ for the test to tell them apart";

    // Channels B,G,R: red of the output is blue of the file; alpha 1.
    Result swapped = cli({"run", copyGraph(tmp, pattern, "B,G,R").string(), "--out",
                          (tmp / "b").string(), "--size", "32x32", "--frames", "1", "--quiet"});
    ASSERT_EQ(swapped.code, 0) << swapped.describe();
    const std::vector<float> in = pixels(seq / "pt.radiance.frame0000.exr");
    const std::vector<float> out = pixels(tmp / "b" / "src.color.exr");
    ASSERT_EQ(in.size(), out.size());
    for (size_t p = 0; p < in.size(); p += 4) {
        ASSERT_EQ(out[p], in[p + 2]) << p;
        ASSERT_EQ(out[p + 2], in[p]) << p;
        ASSERT_EQ(out[p + 3], 1.0f) << p;
    }
}

// Runs `cli(args)` with `dir` as the working directory (restored afterwards).
static Result cliIn(const fs::path& dir, const std::vector<std::string>& args) {
    const fs::path before = fs::current_path();
    fs::current_path(dir);
    Result r = cli(args);
    fs::current_path(before);
    return r;
}

// The README's two commands in a scratch folder laid out like the repository (graphs/ holds a copy
// of the shipped graph): a relative ImageFile path is resolved against the graph file's folder, so
// the graph runs from the root and from any other working directory; a relative --set path is
// resolved against the working directory. Before, ImageFile read relative paths from the working
// directory and the shipped graph only worked from the repository root.
TEST(CliImageFile, ShippedDenoiseGraphRunsFromAnyWorkingDirectory) {
    TempDir tmp;
    fs::create_directories(tmp / "graphs");
    fs::create_directories(tmp / "elsewhere");
    fs::copy_file(kDenoiseGraph, tmp / "graphs" / "denoise_exr_sequence.json");
    Result seq =
        cliIn(tmp.path(), {"run", kPathTraceGraph.string(), "--out", "out/pathtrace_seq", "--size",
                           "32x32", "--frames", "2", "--save-frames", "all", "--quiet"});
    ASSERT_EQ(seq.code, 0) << seq.describe();
    const fs::path graph = tmp / "graphs" / "denoise_exr_sequence.json";
    const std::vector<std::string> common = {"--size", "32x32", "--frames", "2", "--quiet"};
    auto run = [&](const fs::path& cwd, const std::string& graphArg, const std::string& out,
                   std::vector<std::string> extra) {
        std::vector<std::string> args = {"run", graphArg, "--out", (tmp / out).string()};
        args.insert(args.end(), common.begin(), common.end());
        args.insert(args.end(), extra.begin(), extra.end());
        return cliIn(cwd, args);
    };
    Result fromRoot = run(tmp.path(), "graphs/denoise_exr_sequence.json", "d1", {});
    ASSERT_EQ(fromRoot.code, 0) << fromRoot.describe();
    Result fromElsewhere = run(tmp / "elsewhere", graph.string(), "d2", {});
    ASSERT_EQ(fromElsewhere.code, 0) << fromElsewhere.describe();
    Result setFromCwd = run(tmp.path(), graph.string(), "d3",
                            {"--set", "src.path=out/pathtrace_seq/pt.radiance.frame%04d.exr"});
    ASSERT_EQ(setFromCwd.code, 0) << setFromCwd.describe();
    // A --set path relative to another working directory does not exist there: the error names
    // the file as resolved from that directory.
    expectInputError(run(tmp / "elsewhere", graph.string(), "d4",
                         {"--set", "src.path=out/pathtrace_seq/pt.radiance.frame%04d.exr"}),
                     {(tmp / "elsewhere" / "out" / "pathtrace_seq").string()});

    const std::vector<float> noisy =
        pixels(tmp / "out" / "pathtrace_seq" / "pt.radiance.frame0001.exr");
    const std::vector<float> denoised = pixels(tmp / "d1" / "denoise.denoised.frame0001.exr");
    ASSERT_EQ(noisy.size(), denoised.size());
    EXPECT_NE(noisy, denoised) << "ATrousNH changed nothing";
    EXPECT_EQ(denoised, pixels(tmp / "d2" / "denoise.denoised.frame0001.exr"));
    EXPECT_EQ(denoised, pixels(tmp / "d3" / "denoise.denoised.frame0001.exr"));
    EXPECT_TRUE(fs::exists(tmp / "d1" / "tm.ldr.frame0001.png"));
    // The pass contract: ImageFile's staging copy and ATrousNH's indirect arguments are graph
    // fields, so no pass of either run allocates device memory itself.
    for (const char* out : {"d1", "out/pathtrace_seq"}) {
        const json report = readReport(tmp / out);  // a named object: the loop reads into it
        for (const auto& p : report.at("passes"))
            EXPECT_EQ(p.at("allocations_outside_plan"), 0) << out << ": " << p.at("name");
    }
}

TEST(CliImageFile, BadFilesAreInputErrorsNamingTheFile) {
    TempDir tmp;
    const fs::path seq = writeSequence(tmp);
    const std::string pattern = (seq / "pt.radiance.frame%04d.exr").string();
    const std::string graph = copyGraph(tmp, pattern, "").string();
    auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = {"run",     graph,        "--out", (tmp / "o").string(),
                                         "--quiet", "--overwrite"};
        args.insert(args.end(), extra.begin(), extra.end());
        return cli(args);
    };
    expectInputError(run({"--size", "16x16", "--frames", "1"}),
                     {(seq / "pt.radiance.frame0000.exr").string(), "32x32", "16x16"});
    expectInputError(run({"--size", "32x32", "--frames", "3"}),
                     {(seq / "pt.radiance.frame0002.exr").string()});
    expectInputError(run({"--size", "32x32", "--set", "src.channels=albedo.R"}),
                     {"pt.radiance.frame0000.exr", "no channel 'albedo.R'", "R, G, B, A"});
    expectInputError(run({"--size", "32x32", "--set", "src.path=" + (seq / "x%s").string()}),
                     {"src", "frame pattern"});
    expectInputError(run({"--size", "32x32", "--set", "src.path="}), {"src", "'path' is empty"});
}

namespace {

// A 57-byte PNG whose header claims width x height RGBA8 pixels and which holds none.
void writeHeaderOnlyPng(const fs::path& path, uint32_t width, uint32_t height) {
    auto be32 = [](uint32_t v) {
        return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
    };
    auto crc32 = [](const std::string& bytes) {  // PNG's CRC (ISO 3309), bit by bit
        uint32_t c = 0xFFFFFFFFu;
        for (unsigned char b : bytes) {
            c ^= b;
            for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
        }
        return c ^ 0xFFFFFFFFu;
    };
    auto chunk = [&](const std::string& type, const std::string& data) {
        return be32(uint32_t(data.size())) + type + data + be32(crc32(type + data));
    };
    const std::string ihdr = be32(width) + be32(height) + std::string{8, 6, 0, 0, 0};
    writeText(path, std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", "") +
                        chunk("IEND", ""));
}

}  // namespace

TEST(CliImageFile, HugeHeadersAreRefusedBeforeAnyPixelIsDecoded) {
    // Issue 33, class 2: the size in an image's header is checked before the decode allocates.
    // A 57-byte PNG claiming 100000 x 100000 used to end in exit 1 std::bad_alloc; as an
    // ImageFile of the wrong size, a compared image or a reference it is now exit 2 naming it.
    TempDir tmp;
    const fs::path huge = tmp / "huge.png";
    writeHeaderOnlyPng(huge, 100000, 100000);
    const fs::path graph = copyGraph(tmp, huge.string(), "");
    expectInputError(
        cli({"run", graph.string(), "--out", (tmp / "o").string(), "--size", "32x32", "--quiet"}),
        {huge.string(), "100000x100000", "32x32"});
    const fs::path small = tmp / "small.png";
    writeHeaderOnlyPng(small, 16, 16);
    expectInputError(cli({"compare", huge.string(), small.string()}),
                     {huge.string(), "100000x100000", "16x16", "different sizes"});
    expectInputError(cli({"compare", huge.string(), huge.string()}),
                     {huge.string(), "more than the 268435456 pixels allowed"});
    expectInputError(cli({"run", kPathTraceGraph.string(), "--out", (tmp / "r").string(), "--size",
                          "32x32", "--frames", "1", "--reference", huge.string()}),
                     {huge.string(), "100000x100000", "32x32"});
}

TEST(CliImageFile, ValidateRefusesWhatRunWouldWithThePointer) {
    // Issue 33, class 4: malformed frame patterns used to validate and then fail `run` without the
    // graph file or pointer. validate() now refuses them with /passes/0/params/path.
    TempDir tmp;
    for (const char* pattern : {"x%n.exr", "x%d%d.exr", "%", "x%s.exr"}) {
        const fs::path graph = copyGraph(tmp, pattern, "");
        Result r = cli({"validate", graph.string()});
        expectInputError(r, {graph.string(), "/passes/0/params/path", "frame pattern"});
    }
    const fs::path graph = copyGraph(tmp, "a.exr", "R,G,B,A,Z");
    expectInputError(cli({"validate", graph.string()}),
                     {graph.string(), "/passes/0/params/channels", "at most 4"});
}
