// `fovea inspect` in a real window under Xvfb, with the validation layer on (FOVEA_VALIDATION=1
// from ctest): a scripted run whose screenshots are checked for content, parameter changes, node
// colours by status and a broken reload that keeps the graph running; and the no-display error.
#include <gtest/gtest.h>

#include "tests/editor/InspectorTestUtil.h"

namespace fovea::clitest {
namespace {

TEST(Inspector, ScriptedRunUnderXvfb) {
    const std::string xvfb = xvfbPrefix();
    ASSERT_FALSE(xvfb.empty()) << "xvfb-run not found: install xvfb (scripts/install-deps.sh); "
                                  "the inspector tests need a virtual display";
    TempDir dir;
    // The broken file: tm.exposure of the wrong type.
    json broken = json::parse(readText(kStatuses));
    broken["passes"][1]["params"]["exposure"] = "bright";
    writeText(dir / "broken.json", broken.dump(2));
    writeText(dir / "script.txt",
              "0 preview tm.ldr\n"
              "0 select tm\n"
              "3 screenshot " +
                  (dir / "a.png").string() +
                  "  # odd frame: blit bypassed\n"
                  "4 set tm.exposure -4\n"
                  "5 screenshot " +
                  (dir / "b.png").string() +
                  "\n"
                  "6 reload " +
                  (dir / "broken.json").string() + "\n");
    const Result r =
        shellRun(xvfb, {"inspect", kStatuses.string(), "--size", "64x64", "--window", "800x600",
                        "--frames", "8", "--script", (dir / "script.txt").string(), "--screenshot",
                        (dir / "c.png").string()});
    ASSERT_EQ(r.code, 0) << r.describe();
    EXPECT_FALSE(contains(r.err, "validation")) << r.describe();

    const Shot a = readShot(dir / "a.png"), b = readShot(dir / "b.png"),
               c = readShot(dir / "c.png");
    EXPECT_EQ(a.pixels.width, 800u);
    EXPECT_EQ(a.pixels.height, 600u);
    EXPECT_EQ(a.info["preview"]["resource"], "tm.ldr");
    EXPECT_EQ(a.info["selected"], "tm");
    // The preview holds the tone-mapped gradient: not blank, and it varies across the image.
    const auto [meanA, sdA] = previewStats(a);
    EXPECT_GT(meanA, 0.15) << "preview looks blank";
    EXPECT_GT(sdA, 0.05) << "preview has no structure (the gradient)";
    // Four stops down: clearly darker.
    const auto [meanB, sdB] = previewStats(b);
    EXPECT_LT(meanB, meanA * 0.7) << meanA << " -> " << meanB;
    // The broken reload: the error names the JSON pointer, the last good graph keeps running
    // (same preview as before the reload).
    const std::string error = c.info["error"];
    EXPECT_TRUE(contains(error, "/passes/1/params/exposure")) << error;
    EXPECT_TRUE(contains(error, "keeps running")) << error;
    const auto [meanC, sdC] = previewStats(c);
    EXPECT_NEAR(meanC, meanB, 0.01);
    (void)sdB;
    (void)sdC;

    // Node colours match the statuses of the frame (frame 3: src cached, blit bypassed).
    std::map<std::string, std::string> expected{
        {"src", "cached"}, {"noise", "executed"}, {"blit", "bypassed"}, {"unused", "culled"}};
    size_t checked = 0;
    for (const auto& node : a.info["nodes"]) {
        const std::string name = node["name"];
        if (expected.count(name)) {
            EXPECT_EQ(node["status"], expected[name]) << name;
        }
        if (!node["visible"].get<bool>()) continue;
        const auto h = node["header"];
        const int x = int(float(h[0]) + float(h[2]) * 0.5f), y = int(float(h[1]) + float(h[3]) - 2);
        const float* p = &a.pixels.pixels[(size_t(y) * a.pixels.width + size_t(x)) * 4];
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(p[k] * 255.0f, node["colour"][k].get<float>(), 6.0f)
                << name << " (" << node["status"] << ") channel " << k << " at " << x << "," << y;
        ++checked;
    }
    EXPECT_EQ(checked, 5u) << "every node of the small graph is visible in an 800x600 window";
}

// The colour of the previewed image at (u, v) in [0,1]^2 of the image, 0..255.
std::array<int, 3> previewColour(const Shot& s, float u, float v) {
    const auto r = s.info["preview"]["image"];
    const int x = int(r[0].get<float>() + u * r[2].get<float>());
    const int y = int(r[1].get<float>() + v * r[3].get<float>());
    const float* p = &s.pixels.pixels[(size_t(y) * s.pixels.width + size_t(x)) * 4];
    return {int(std::lround(p[0] * 255)), int(std::lround(p[1] * 255)),
            int(std::lround(p[2] * 255))};
}

TEST(Inspector, ScriptedGazeMovesTheFovea) {
    const std::string xvfb = xvfbPrefix();
    ASSERT_FALSE(xvfb.empty()) << "xvfb-run not found: install xvfb (scripts/install-deps.sh)";
    TempDir dir;
    writeText(dir / "script.txt",
              "0 falsecolour on\n"
              "1 screenshot " +
                  (dir / "a.png").string() +
                  "\n"
                  "2 gaze 0.2 0.2\n"
                  "2 screenshot " +
                  (dir / "b.png").string() +
                  "\n"
                  "3 screenshot " +
                  (dir / "c.png").string() + "\n");
    const Result r = shellRun(
        xvfb, {"inspect", (kRepo / "graphs" / "tests" / "inspector_gaze.json").string(), "--window",
               "640x480", "--frames", "4", "--script", (dir / "script.txt").string()});
    ASSERT_EQ(r.code, 0) << r.describe();
    const Shot a = readShot(dir / "a.png"), b = readShot(dir / "b.png"),
               c = readShot(dir / "c.png");
    // The fovea (the false-colour ramp's top: every pixel sampled) follows the gaze: at the
    // centre before, at (0.2, 0.2) after; the centre is no longer fovea.
    const auto foveaBefore = previewColour(a, 0.5f, 0.5f);
    EXPECT_GT(foveaBefore[0], 150) << "the gaze point should be in the fovea (red end of the ramp)";
    EXPECT_EQ(previewColour(c, 0.2f, 0.2f), foveaBefore);
    EXPECT_NE(previewColour(c, 0.5f, 0.5f), foveaBefore);
    // FoveationMask is cached while the gaze stays, and runs again in the frame it moves.
    EXPECT_EQ(a.info["nodes"][0]["status"], "cached");
    EXPECT_EQ(b.info["nodes"][0]["status"], "executed");
    EXPECT_EQ(c.info["nodes"][0]["status"], "cached");
}

TEST(Inspector, NoDisplayExitsOneWithMessage) {
    const Result r = shellRun("env -u DISPLAY -u WAYLAND_DISPLAY",
                              {"inspect", kStatuses.string(), "--frames", "1"});
    EXPECT_EQ(r.code, 1) << r.describe();
    EXPECT_TRUE(contains(r.err, "needs a display")) << r.describe();
}

TEST(Inspector, BadScriptIsInputError) {
    TempDir dir;
    writeText(dir / "script.txt", "0 selectt tm\n");
    const Result r = shellRun("env -u DISPLAY", {"inspect", kStatuses.string(), "--frames", "1",
                                                 "--script", (dir / "script.txt").string()});
    expectInputError(r, {"script.txt:1", "unknown command 'selectt'", "did you mean 'select'"});
}

TEST(Inspector, ScreenshotNeverReplacesAFileSilently) {
    TempDir dir;
    writeText(dir / "shot.png", "keep me");
    const Result r = shellRun("env -u DISPLAY", {"inspect", kStatuses.string(), "--frames", "1",
                                                 "--screenshot", (dir / "shot.png").string()});
    expectInputError(r, {"--screenshot", "shot.png' exists", "--overwrite"});
    EXPECT_EQ(readText(dir / "shot.png"), "keep me");
}

}  // namespace
}  // namespace fovea::clitest
