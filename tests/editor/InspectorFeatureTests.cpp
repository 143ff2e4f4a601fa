// `fovea inspect` features driven by --script under Xvfb with the validation layer on: the second
// image with the difference view, edge preview, zoom, preview screenshots (EXR equal to the
// field's read-back by `fovea run`), save as (parameters + node positions that load back), free-fly
// camera, and parameter edits applied in place.
#include <gtest/gtest.h>

#include "tests/editor/InspectorTestUtil.h"

namespace fovea::clitest {
namespace {

// Mean of |a - b| over every channel (sizes must match).
double meanAbsDiff(const image::ImageRGBA& a, const image::ImageRGBA& b) {
    EXPECT_EQ(a.pixels.size(), b.pixels.size());
    double sum = 0;
    for (size_t i = 0; i < std::min(a.pixels.size(), b.pixels.size()); ++i)
        sum += std::abs(double(a.pixels[i]) - double(b.pixels[i]));
    return a.pixels.empty() ? 0.0 : sum / double(a.pixels.size());
}

// Mean RGB (0..1) of the window pixels inside rect [x, y, w, h].
double rectMean(const Shot& s, const json& rect) {
    const int x0 = rect[0], y0 = rect[1], w = rect[2], h = rect[3];
    double sum = 0;
    for (int y = y0; y < y0 + h; ++y)
        for (int x = x0; x < x0 + w; ++x)
            for (int c = 0; c < 3; ++c)
                sum += s.pixels.pixels[(size_t(y) * s.pixels.width + size_t(x)) * 4 + size_t(c)];
    return w * h > 0 ? sum / double(w * h * 3) : -1.0;
}

std::array<float, 3> windowPixel(const Shot& s, int x, int y) {
    const float* p = &s.pixels.pixels[(size_t(y) * s.pixels.width + size_t(x)) * 4];
    return {p[0], p[1], p[2]};
}

TEST(Inspector, CompareDifferenceZoomEdgeAndPreviewShots) {
    const std::string xvfb = xvfbPrefix();
    ASSERT_FALSE(xvfb.empty()) << "xvfb-run not found: install xvfb (scripts/install-deps.sh)";
    TempDir dir;
    image::ImageRGBA ref{64, 64, std::vector<float>(64 * 64 * 4, 0.5f)};
    for (size_t p = 0; p < 64 * 64; ++p) ref.pixels[p * 4 + 3] = 1.0f;
    image::writeExr(dir / "ref.exr", ref);
    auto at = [&](const std::string& name) { return (dir / name).string(); };
    writeText(dir / "script.txt",
              "0 preview src.color\n"
              "1 previewshot " +
                  at("src.exr") +
                  "\n"
                  "2 preview tm.color  # the edge src.color -> tm.color\n"
                  "2 previewshot " +
                  at("edge.exr") +
                  "\n"
                  "3 preview src.color\n"
                  "3 compare src.color\n"
                  "3 difference on\n"
                  "3 screenshot " +
                  at("self.png") +
                  "\n"
                  "4 compare reference\n"
                  "4 previewshot " +
                  at("diff.exr") +
                  "\n"
                  "4 screenshot " +
                  at("ref.png") +
                  "\n"
                  "5 difference off\n"
                  "5 compare off\n"
                  "5 zoom 4 0.26 0.26\n"
                  "5 preview tm.ldr\n"
                  "5 previewshot " +
                  at("ldr.exr") +
                  "\n"
                  "5 previewshot " +
                  at("ldr.png") +
                  "\n"
                  "5 screenshot " +
                  at("zoom.png") + "\n");
    const Result r = shellRun(
        xvfb, {"inspect", kStatuses.string(), "--size", "64x64", "--window", "800x600", "--frames",
               "6", "--script", at("script.txt"), "--reference", at("ref.exr")});
    ASSERT_EQ(r.code, 0) << r.describe();

    // The edge carries the field it comes from: identical floats.
    const image::ImageRGBA src = image::readImage(dir / "src.exr");
    ASSERT_EQ(src.width, 64u);
    EXPECT_EQ(image::readImage(dir / "edge.exr").pixels, src.pixels);
    EXPECT_NE(src.pixels[0], src.pixels[(64 * 64 - 1) * 4]) << "the gradient varies";
    // The difference view against the reference: |src - 0.5| per channel, alpha 1.
    const image::ImageRGBA diff = image::readImage(dir / "diff.exr");
    ASSERT_EQ(diff.pixels.size(), src.pixels.size());
    for (size_t i = 0; i < diff.pixels.size(); ++i)
        ASSERT_FLOAT_EQ(diff.pixels[i], i % 4 == 3 ? 1.0f : std::abs(src.pixels[i] - 0.5f)) << i;

    // On screen: a field compared with itself differs nowhere (right pane black), the left pane
    // shows the gradient; against the reference the right pane is not black.
    const Shot self = readShot(dir / "self.png"), refShot = readShot(dir / "ref.png");
    EXPECT_TRUE(self.info["compare"]["difference"].get<bool>());
    EXPECT_GT(self.info["compare"]["image"][2].get<int>(), 50);
    EXPECT_LT(rectMean(self, self.info["compare"]["image"]), 0.01);
    EXPECT_GT(rectMean(self, self.info["preview"]["image"]), 0.15);
    EXPECT_GT(rectMean(refShot, refShot.info["compare"]["image"]), 0.05);
    EXPECT_EQ(refShot.info["compare"]["resource"], "reference");

    // Zoom x4 on (0.26, 0.26): the image fills the pane and its centre shows that point.
    const Shot zoom = readShot(dir / "zoom.png");
    EXPECT_EQ(zoom.info["preview"]["zoom"].get<float>(), 4.0f);
    EXPECT_EQ(zoom.info["preview"]["image"], zoom.info["preview"]["rect"]);
    const auto rect = zoom.info["preview"]["rect"];
    const auto centre = windowPixel(zoom, rect[0].get<int>() + rect[2].get<int>() / 2,
                                    rect[1].get<int>() + rect[3].get<int>() / 2);
    // tm.ldr at (0.26, 0.26) of the 64x64 image is pixel (16, 16) of ldr.exr (display-encoded).
    const image::ImageRGBA ldr = image::readImage(dir / "ldr.exr");
    ASSERT_EQ(ldr.width, 64u);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(centre[size_t(c)], ldr.pixels[(16 * 64 + 16) * 4 + size_t(c)], 2.5 / 255.0)
            << "channel " << c;

    // The preview EXR equals the field `fovea run` reads back (an independent path).
    const Result run = cli({"run", kStatuses.string(), "--size", "64x64", "--frames", "1", "--out",
                            at("run"), "--quiet"});
    ASSERT_EQ(run.code, 0) << run.describe();
    EXPECT_EQ(ldr.pixels, image::readImage(dir / "run" / "tm.ldr.exr").pixels);
    // The PNG is the field as shown: an 8-bit field is written as it is.
    const image::ImageRGBA ldrPng = image::readImage(dir / "ldr.png");
    ASSERT_EQ(ldrPng.width, 64u);
    EXPECT_LT(meanAbsDiff(ldrPng, ldr), 1.0 / 255.0);
}

TEST(Inspector, SaveAsWritesParamsAndPositionsThatLoadBack) {
    const std::string xvfb = xvfbPrefix();
    ASSERT_FALSE(xvfb.empty()) << "xvfb-run not found: install xvfb (scripts/install-deps.sh)";
    TempDir dir;
    auto at = [&](const std::string& name) { return (dir / name).string(); };
    writeText(dir / "script.txt",
              "0 set tm.exposure -2\n"
              "0 place tm 420 30\n"
              "1 saveas " +
                  at("saved.json") +
                  "\n"
                  "1 screenshot " +
                  at("first.png") + "\n");
    const Result r = shellRun(xvfb, {"inspect", kStatuses.string(), "--window", "800x600",
                                     "--frames", "2", "--script", at("script.txt")});
    ASSERT_EQ(r.code, 0) << r.describe();
    const Shot first = readShot(dir / "first.png");
    // The exposure edit was applied in place: only the tone mapper recompiled, no new pipeline.
    EXPECT_EQ(first.info["last_change"]["what"], "set tm.exposure");
    EXPECT_TRUE(first.info["last_change"]["in_place"].get<bool>());
    EXPECT_EQ(first.info["last_change"]["recompiled"], json::array({"tm"}));
    EXPECT_EQ(first.info["last_change"]["pipelines_created"], 0);

    const json saved = json::parse(readText(dir / "saved.json"));
    EXPECT_EQ(saved["passes"][1]["params"]["exposure"], -2.0);
    EXPECT_EQ(saved["passes"][1]["params"]["operator"], "aces") << "other params kept";
    EXPECT_EQ(saved["editor"]["nodes"]["tm"], json::array({420.0, 30.0}));
    std::map<std::string, json> positions;
    for (const auto& node : first.info["nodes"]) positions[node["name"]] = node["position"];
    ASSERT_EQ(saved["editor"]["nodes"].size(), positions.size());

    // Loaded back: the same parameters and every node where it was saved.
    const Result again = shellRun(xvfb, {"inspect", at("saved.json"), "--window", "800x600",
                                         "--frames", "1", "--screenshot", at("loaded.png")});
    ASSERT_EQ(again.code, 0) << again.describe();
    const Shot loaded = readShot(dir / "loaded.png");
    for (const auto& node : loaded.info["nodes"]) {
        const json& p = saved["editor"]["nodes"][node["name"].get<std::string>()];
        EXPECT_EQ(node["position"][0].get<float>(), p[0].get<float>()) << node["name"];
        EXPECT_EQ(node["position"][1].get<float>(), p[1].get<float>()) << node["name"];
    }
    // Same parameters as the edited graph: the same tone-mapped picture.
    EXPECT_NEAR(previewStats(loaded).first, previewStats(first).first, 0.01);
}

TEST(Inspector, SaveAsNeverReplacesAFileSilently) {
    TempDir dir;
    writeText(dir / "taken.json", "keep me");
    writeText(dir / "script.txt", "0 saveas " + (dir / "taken.json").string() + "\n");
    const Result r = shellRun("env -u DISPLAY", {"inspect", kStatuses.string(), "--frames", "1",
                                                 "--script", (dir / "script.txt").string()});
    expectInputError(r, {"script.txt:1", "taken.json' exists", "--overwrite"});
    EXPECT_EQ(readText(dir / "taken.json"), "keep me");
}

TEST(Inspector, FreeFlyMovesTheCamera) {
    const std::string xvfb = xvfbPrefix();
    ASSERT_FALSE(xvfb.empty()) << "xvfb-run not found: install xvfb (scripts/install-deps.sh)";
    TempDir dir;
    auto at = [&](const std::string& name) { return (dir / name).string(); };
    writeText(dir / "script.txt",
              "0 preview gb.albedo\n"
              "1 previewshot " +
                  at("path.exr") +
                  "\n"
                  "2 camera freefly\n"
                  "2 previewshot " +
                  at("start.exr") +
                  "\n"
                  "3 look 25 0\n"
                  "3 previewshot " +
                  at("turned.exr") +
                  "\n"
                  "3 screenshot " +
                  at("turned.png") +
                  "\n"
                  "4 move 0 0 300  # builtin:cornell is about 550 units wide\n"
                  "4 previewshot " +
                  at("moved.exr") +
                  "\n"
                  "5 camera path\n"
                  "5 previewshot " +
                  at("back.exr") + "\n");
    const Result r = shellRun(
        xvfb, {"inspect", (kRepo / "graphs" / "tests" / "golden_gbuffer.json").string(), "--size",
               "64x64", "--window", "640x480", "--frames", "6", "--script", at("script.txt")});
    ASSERT_EQ(r.code, 0) << r.describe();
    const auto path = image::readImage(dir / "path.exr");
    // Free-fly starts at the path's pose: the same picture; turning and moving change it; the
    // path brings the first picture back.
    // (the pose goes through yaw/pitch and back: equal up to rounding at a few edge pixels)
    EXPECT_LT(meanAbsDiff(image::readImage(dir / "start.exr"), path), 1e-3);
    const auto turned = image::readImage(dir / "turned.exr");
    EXPECT_GT(meanAbsDiff(turned, path), 0.02);
    EXPECT_GT(meanAbsDiff(image::readImage(dir / "moved.exr"), turned), 0.005);
    EXPECT_EQ(image::readImage(dir / "back.exr").pixels, path.pixels);
    const Shot shot = readShot(dir / "turned.png");
    EXPECT_EQ(shot.info["camera"]["mode"], "freefly");
}

}  // namespace
}  // namespace fovea::clitest
