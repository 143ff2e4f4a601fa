// Inspector pieces without a window or GPU: zoom, pan and the two panes of a comparison
// (editor/PreviewImage), the free-fly camera (editor/FreeFlyCamera) and node positions from and
// into the graph file's editor block (editor/GraphLayout).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/graph/CompilerStages.h"
#include "core/graph/PassRegistry.h"
#include "editor/FreeFlyCamera.h"
#include "editor/GraphLayout.h"
#include "editor/PreviewImage.h"
#include "passes/RegisterPasses.h"

namespace fovea::editor {
namespace {

// 4x4 image whose red channel is the pixel index (x + 4y).
image::ImageRGBA indexImage() {
    image::ImageRGBA img{4, 4, std::vector<float>(64, 1.0f)};
    for (size_t p = 0; p < 16; ++p) img.pixels[p * 4] = float(p);
    return img;
}

TEST(PreviewView, ZoomPanAndPanes) {
    const image::ImageRGBA img = indexImage();
    PreviewSettings s;
    PreviewFit fit;
    // 8x8 pane: fitted, 2 pixels per image pixel; pixel (3, 3) of the image under (7, 7).
    PreviewBlit blit = makePreview(img, 100, 50, 8, 8, s, false, &fit);
    EXPECT_EQ(fit.scale, 2.0f);
    auto px = previewPixelAt(blit, fit, 107.5f, 57.5f);
    ASSERT_TRUE(px);
    EXPECT_EQ(*px, std::make_pair(3u, 3u));
    // Zoom x2 centred on the image's centre: 4 pixels per image pixel, pixels (1..2) visible.
    s.view = {2.0f, 0.5f, 0.5f};
    blit = makePreview(img, 100, 50, 8, 8, s, false, &fit);
    EXPECT_EQ(fit.scale, 4.0f);
    EXPECT_EQ(*previewPixelAt(blit, fit, 100.5f, 50.5f), std::make_pair(1u, 1u));
    EXPECT_EQ(*previewPixelAt(blit, fit, 107.5f, 57.5f), std::make_pair(2u, 2u));
    EXPECT_EQ(visibleImageRect(blit, fit), (std::array<int, 4>{100, 50, 8, 8}));
    // Zooming around a point keeps that point under the pointer.
    PreviewView view;
    blit = makePreview(img, 0, 0, 8, 8, {}, false, &fit);
    const auto before = *previewPixelAt(blit, fit, 1.5f, 1.5f);
    zoomAround(view, fit, 2.0f, 1.5f, 1.5f);
    s.view = view;
    blit = makePreview(img, 0, 0, 8, 8, s, false, &fit);
    EXPECT_EQ(*previewPixelAt(blit, fit, 1.5f, 1.5f), before);
    // Pan by 4 window pixels to the left = one image pixel at 4 pixels per image pixel.
    const auto under = *previewPixelAt(blit, fit, 4.5f, 4.5f);
    panBy(s.view, fit, -4.0f, 0.0f);
    blit = makePreview(img, 0, 0, 8, 8, s, false, &fit);
    EXPECT_EQ(previewPixelAt(blit, fit, 4.5f, 4.5f)->first, under.first + 1);

    // Two panes: the right one maps its own columns; the left one does not reach into it.
    PreviewBlit two{0, 0, 18, 8, std::vector<uint8_t>(18 * 8 * 4, 0)};
    PreviewFit left, right;
    drawPreviewPane(img, {}, false, two, 0, 8, &left);
    drawPreviewPane(img, {}, false, two, 10, 8, &right);
    EXPECT_FALSE(previewPixelAt(two, left, 11.0f, 1.0f));
    EXPECT_EQ(*previewPixelAt(two, right, 10.5f, 0.5f), std::make_pair(0u, 0u));
    // Red of pixel 15 = 15 -> clamps to 255 in both panes.
    EXPECT_EQ(two.bytes[(7 * 18 + 17) * 4], 255);
    EXPECT_EQ(two.bytes[(7 * 18 + 7) * 4], 255);
}

TEST(PreviewView, DifferenceAndDisplayImage) {
    const image::ImageRGBA a = indexImage();
    image::ImageRGBA b = a;
    b.pixels[4] = 3.0f;  // pixel 1: red 1 -> 3
    const image::ImageRGBA d = differenceImage(a, b);
    ASSERT_EQ(d.width, 4u);
    EXPECT_EQ(d.pixels[4], 2.0f);
    EXPECT_EQ(d.pixels[0], 0.0f);
    EXPECT_EQ(d.pixels[7], 1.0f);  // alpha
    EXPECT_TRUE(differenceImage(a, image::ImageRGBA{2, 2, std::vector<float>(16)}).pixels.empty());
    // Display image: linear 0.5 -> sRGB 188/255 at its own size.
    image::ImageRGBA half{1, 1, {0.5f, 0.5f, 0.5f, 1.0f}};
    const image::ImageRGBA shown = displayImage(half, {});
    EXPECT_FLOAT_EQ(shown.pixels[0], 188.0f / 255.0f);
}

TEST(FreeFlyCamera, MoveAndLook) {
    scene::CameraDesc pose;
    pose.position = {0, 0, 5};
    pose.target = {0, 0, 0};
    FreeFlyCamera fly(pose);
    EXPECT_NEAR(glm::length(fly.forward() - glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(fly.pose().target - pose.target), 0.0f, 1e-5f);
    EXPECT_NEAR(fly.step(), 0.1f, 1e-6f);  // 2% of the distance to the target
    fly.move({0, 0, 1});                   // forward
    EXPECT_NEAR(fly.position().z, 4.0f, 1e-5f);
    fly.move({1, 0, 0});  // right of -Z is +X
    EXPECT_NEAR(fly.position().x, 1.0f, 1e-5f);
    fly.look(90, 0);  // turn right: now looking down +X
    EXPECT_NEAR(glm::length(fly.forward() - glm::vec3(1, 0, 0)), 0.0f, 1e-5f);
    fly.look(0, 200);  // the pitch stops short of the pole
    EXPECT_LT(fly.forward().y, 1.0f);
    EXPECT_GT(fly.forward().y, 0.99f);
}

TEST(GraphLayout, SavedPositionsRoundTrip) {
    registerBuiltinPasses();
    const auto file = std::filesystem::path(FOVEA_TEST_DIR).parent_path() / "graphs" / "tests" /
                      "inspector_statuses.json";
    graph::CompileOptions options;
    options.width = options.height = 64;
    const auto plan =
        graph::compileGraphPlan(graph::parseGraphFile(file), graph::passRegistry(), options);
    std::string problems;
    const nlohmann::json block = {{"zoom", 2},
                                  {"nodes", {{"tm", {500, 40}}, {"src", "left"}, {"x", {1, 2}}}}};
    const NodePositions positions = readNodePositions(block, problems);
    EXPECT_NE(problems.find("editor.nodes.src: expected [x, y]"), std::string::npos) << problems;
    ASSERT_EQ(positions.count("tm"), 1u);
    const GraphLayout placed = layoutGraph(plan, {}, &positions);
    const size_t tm = plan.findNode("tm");
    EXPECT_EQ(placed.nodes[tm].x, 500.0f);
    EXPECT_EQ(placed.nodes[tm].y, 40.0f);
    EXPECT_EQ(placed.nodes[tm].inputs[0].x, 500.0f) << "slots follow the node";
    EXPECT_GE(placed.width, 500.0f + placed.nodes[tm].width);
    // Written back: every node, other editor keys kept; read again: the same layout.
    const nlohmann::json written = writeNodePositions(block, placed);
    EXPECT_EQ(written["zoom"], 2);
    EXPECT_EQ(written["nodes"].size(), plan.nodes.size());
    problems.clear();
    const NodePositions again = readNodePositions(written, problems);
    EXPECT_TRUE(problems.empty()) << problems;
    // Positions are saved in whole pixels (readable files): the reloaded layout is the placed
    // one rounded.
    const GraphLayout reloaded = layoutGraph(plan, {}, &again);
    for (size_t i = 0; i < plan.nodes.size(); ++i) {
        EXPECT_EQ(reloaded.nodes[i].x, std::round(placed.nodes[i].x)) << plan.nodes[i].name;
        EXPECT_EQ(reloaded.nodes[i].y, std::round(placed.nodes[i].y)) << plan.nodes[i].name;
    }
}

}  // namespace
}  // namespace fovea::editor
