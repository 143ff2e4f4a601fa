// editor/GraphLayout and editor/PreviewImage without a window or GPU: node positions on every
// shipped graph, no overlaps, edges between the right slots; the preview's pixel conversion.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/graph/CompilerStages.h"
#include "core/graph/PassRegistry.h"
#include "core/scene/SceneFeatures.h"
#include "editor/GraphLayout.h"
#include "editor/PreviewImage.h"
#include "passes/RegisterPasses.h"

namespace fovea::editor {
namespace {

namespace fs = std::filesystem;
const fs::path kRepo = fs::path(FOVEA_TEST_DIR).parent_path();

std::vector<fs::path> shippedGraphs() {
    std::vector<fs::path> out;
    for (const fs::path& dir : {kRepo / "graphs", kRepo / "graphs" / "tests"})
        for (const auto& entry : fs::directory_iterator(dir))
            if (entry.path().extension() == ".json") out.push_back(entry.path());
    std::sort(out.begin(), out.end());
    return out;
}

graph::CompiledPlan compile(const fs::path& file) {
    registerBuiltinPasses();
    graph::CompileOptions options;
    options.width = 64;
    options.height = 64;
    const graph::GraphDesc desc = graph::parseGraphFile(file);
    // As with a scene that has everything (nothing culled for it), seen through the graph's
    // camera model: a pinhole unless its defaults say equirect (the 360° preview graphs), since
    // the foveation passes refuse a 360° camera and PreviewSamples a pinhole.
    options.sceneFeatures = ~0u;
    if (desc.defaults.cameraModel.value_or("perspective") != "equirect")
        options.sceneFeatures &= ~uint32_t(scene::kSceneEquirect);
    return graph::compileGraphPlan(desc, graph::passRegistry(), options);
}

bool overlap(const LayoutNode& a, const LayoutNode& b) {
    return a.x < b.x + b.width && b.x < a.x + a.width && a.y < b.y + b.height &&
           b.y < a.y + a.height;
}

TEST(GraphLayout, EveryShippedGraph) {
    const auto graphs = shippedGraphs();
    ASSERT_GE(graphs.size(), 10u);
    for (const fs::path& file : graphs) {
        SCOPED_TRACE(file.string());
        const graph::CompiledPlan plan = compile(file);
        const GraphLayout layout = layoutGraph(plan);
        ASSERT_EQ(layout.nodes.size(), plan.nodes.size());
        for (size_t i = 0; i < layout.nodes.size(); ++i) {
            const LayoutNode& n = layout.nodes[i];
            EXPECT_EQ(n.name, plan.nodes[i].name);
            EXPECT_GT(n.width, 0);
            EXPECT_GT(n.height, 0);
            EXPECT_LE(n.x + n.width, layout.width);
            EXPECT_LE(n.y + n.height, layout.height);
            // Every slot lies on the node's left (inputs) or right (outputs) border.
            for (const auto& s : n.inputs) {
                EXPECT_EQ(s.x, n.x);
                EXPECT_GT(s.y, n.y);
                EXPECT_LT(s.y, n.y + n.height);
            }
            for (const auto& s : n.outputs) {
                EXPECT_EQ(s.x, n.x + n.width);
                EXPECT_LT(s.y, n.y + n.height);
            }
            for (size_t j = i + 1; j < layout.nodes.size(); ++j)
                EXPECT_FALSE(overlap(n, layout.nodes[j]))
                    << n.name << " / " << layout.nodes[j].name;
        }
        // One drawn edge per connected input, between the slots the plan names; same-frame edges
        // run left to right, and so does the compiled order between columns.
        EXPECT_EQ(layout.edges.size(), plan.inputs.size());
        for (const LayoutEdge& e : layout.edges) {
            const auto& to = layout.nodes[e.toNode];
            const auto& from = layout.nodes[e.fromNode];
            const auto it = plan.inputs.find({e.toNode, to.inputs[e.toSlot].field});
            ASSERT_NE(it, plan.inputs.end());
            EXPECT_EQ(it->second.node, e.fromNode);
            EXPECT_EQ(it->second.field, from.outputs[e.fromSlot].field);
            EXPECT_EQ(it->second.delay, e.delay);
            if (e.delay == 0) {
                EXPECT_LT(from.column, to.column) << from.name << " -> " << to.name;
            }
        }
        for (size_t a = 0; a < plan.order.size(); ++a) {
            for (size_t b = a + 1; b < plan.order.size(); ++b) {
                const LayoutNode& first = layout.nodes[plan.order[a]];
                const LayoutNode& second = layout.nodes[plan.order[b]];
                if (first.column == second.column) {
                    EXPECT_LT(first.row, second.row) << first.name << " / " << second.name;
                }
            }
        }
    }
}

TEST(GraphLayout, DelayEdgesAreMarked) {
    // history_difference reads its own output one frame late: the delay is kept for drawing.
    const GraphLayout layout =
        layoutGraph(compile(kRepo / "graphs" / "tests" / "history_difference.json"));
    size_t delayed = 0;
    for (const auto& e : layout.edges) delayed += e.delay > 0;
    EXPECT_GT(delayed, 0u);
}

TEST(PreviewImage, ExposureChannelFalseColourAndFit) {
    image::ImageRGBA src{2, 1, {0.25f, 0.5f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f}};
    PreviewFit fit;
    // 4x4 rectangle: the 2x1 image scales by 2 into rows 1..2, letterboxed above and below.
    PreviewBlit blit = makePreview(src, 10, 20, 4, 4, {}, false, &fit);
    EXPECT_EQ(fit.scale, 2.0f);
    EXPECT_EQ(fit.offsetY, 1);
    EXPECT_EQ(blit.bytes[(1 * 4 + 0) * 4 + 2], 255);  // blue 1.0 -> 255
    EXPECT_EQ(blit.bytes[(1 * 4 + 0) * 4 + 1], 188);  // sRGB(0.5) = 0.7354
    EXPECT_EQ(blit.bytes[(0 * 4 + 0) * 4 + 0], 24);   // letterbox
    auto px = previewPixelAt(blit, fit, 10 + 3.5f, 20 + 1.5f);
    ASSERT_TRUE(px);
    EXPECT_EQ(px->first, 1u);
    EXPECT_FALSE(previewPixelAt(blit, fit, 10.5f, 20.5f));  // letterbox
    // BGRA order and one stop down: blue ends up in byte 0 and halves (sRGB(0.5)).
    PreviewSettings darker;
    darker.exposure = -1;
    blit = makePreview(src, 0, 0, 2, 1, darker, true);
    EXPECT_EQ(blit.bytes[0], 188);
    // Channel R as grey; false colour maps min..max onto the ramp's ends.
    PreviewSettings red;
    red.channel = PreviewChannel::R;
    blit = makePreview(src, 0, 0, 2, 1, red, false);
    EXPECT_EQ(blit.bytes[0], blit.bytes[1]);
    EXPECT_EQ(blit.bytes[0], 137);  // sRGB(0.25)
    PreviewSettings ramp;
    ramp.falseColour = true;
    blit = makePreview(src, 0, 0, 2, 1, ramp, false);
    EXPECT_GT(blit.bytes[0], blit.bytes[2]);  // max: red end
    EXPECT_LT(blit.bytes[4], blit.bytes[6]);  // min: blue end
    // Non-finite pixels are magenta, never a colour that looks valid.
    src.pixels[0] = std::numeric_limits<float>::quiet_NaN();
    blit = makePreview(src, 0, 0, 2, 1, {}, false);
    EXPECT_EQ(blit.bytes[0], 255);
    EXPECT_EQ(blit.bytes[1], 0);
    EXPECT_EQ(blit.bytes[2], 255);
}

}  // namespace
}  // namespace fovea::editor
