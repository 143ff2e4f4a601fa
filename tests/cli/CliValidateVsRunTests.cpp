// `fovea validate` and `fovea run` agree (issue 30): every check that needs no device runs in
// validate (the compile stages and Pass::validate), so a graph that validates builds and runs,
// and a graph that validate rejects is rejected by run with the same message. Over every shipped
// graph (graphs/, graphs/tests/) and every bad-compile fixture (tests/graph/bad/compile/).
//
// The one deliberate difference: ImageFile checks that its input file exists and has the graph's
// size when the graph is built (its compile()), because validate checks a graph without its
// input data (denoise_exr_sequence.json validates before its input sequence is rendered).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

const std::string kCheckSize = "64x32";  // 2:1, so the equirect preview graphs accept it too

std::vector<fs::path> graphFilesIn(const fs::path& dir) {
    std::vector<fs::path> out;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().extension() == ".json") out.push_back(e.path());
    std::sort(out.begin(), out.end());
    return out;
}

std::string firstLineOf(const std::string& text) {
    return text.substr(0, text.find('\n'));
}

Result validateAtCheckSize(const fs::path& graph) {
    return cli({"validate", graph.string(), "--size", kCheckSize});
}

Result runOneFrameAtCheckSize(const fs::path& graph, const fs::path& out) {
    return cli({"run", graph.string(), "--frames", "1", "--size", kCheckSize, "--out", out.string(),
                "--save-frames", "none", "--quiet"});
}

TEST(CliValidateVsRun, ShippedGraphsThatValidateBuildAndRun) {
    TempDir tmp;
    size_t checked = 0;
    for (const auto& dir : {kRepo / "graphs", kRepo / "graphs" / "tests"}) {
        for (const fs::path& graph : graphFilesIn(dir)) {
            const Result v = validateAtCheckSize(graph);
            EXPECT_EQ(v.code, 0) << v.describe();
            if (v.code != 0) continue;
            const Result r = runOneFrameAtCheckSize(graph, tmp / std::to_string(checked++));
            if (r.code != 0 && contains(readText(graph), "\"ImageFile\"")) {
                // The documented exception: the input file of ImageFile, read at build.
                EXPECT_EQ(r.code, 2) << r.describe();
                EXPECT_TRUE(contains(r.err, "cannot read image")) << r.describe();
                continue;
            }
            EXPECT_EQ(r.code, 0) << "validate accepted " << graph << " but run rejected it\n"
                                 << r.describe();
        }
    }
    EXPECT_GE(checked, 30u);
}

TEST(CliValidateVsRun, FixturesValidateRejectsRunRejectsWithTheSameMessage) {
    TempDir tmp;
    size_t checked = 0;
    for (const fs::path& graph : graphFilesIn(kRepo / "tests" / "graph" / "bad" / "compile")) {
        const Result v = validateAtCheckSize(graph);
        const Result r = runOneFrameAtCheckSize(graph, tmp / std::to_string(checked++));
        EXPECT_EQ(v.code, 2) << v.describe();
        EXPECT_EQ(r.code, 2) << r.describe();
        EXPECT_EQ(firstLineOf(v.err), firstLineOf(r.err)) << graph;
    }
    EXPECT_GE(checked, 20u);
}

}  // namespace
