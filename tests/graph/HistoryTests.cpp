// GPU tests of pass-declared history (FieldBuilder::history, ExecuteContext::previous and
// historyValid, `prev_<field>` bindings): what the pass sees on the first frame, once its ring
// fills, after a camera cut, a reset, a resize and rebuilds that keep or change the field.
// The test pass "FrameStamp" (tests/passes/FrameStampPass.h) writes a stamp per frame and copies
// the previous frames the graph hands it into plain outputs.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/scene/Camera.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"
#include "tests/passes/FrameStampPass.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::graph;

namespace {

const PassRegistry& registry() {
    static const PassRegistry r = [] {
        PassRegistry reg;
        reg.add({"FrameStamp", "", [] { return std::make_unique<test::FrameStampPass>(); }});
        return reg;
    }();
    return r;
}

GraphDesc stampGraph(const std::string& params = "{}") {
    return parseGraphText(R"({ "version": 1, "passes": [ { "name": "s", "type": "FrameStamp",
        "params": )" + params +
                              R"( } ], "outputs": [ "s.stamp", "s.seen1", "s.seen2" ] })",
                          "history_test.json");
}

CompileOptions sized(uint32_t w, uint32_t h) {
    CompileOptions o;
    o.width = w;
    o.height = h;
    return o;
}

class PassHistory : public GpuTest {
protected:
    // Runs one frame and returns the stamp value the pass saw 1 and 2 frames back (-1 = told
    // invalid), checked to be uniform over the image and to carry the right pixel coordinates.
    std::pair<float, float> frame(RenderGraph& g) {
        g.runFrame();
        return {seen(g, "s.seen1"), seen(g, "s.seen2")};
    }
    float seen(RenderGraph& g, const std::string& resource) {
        const auto& img = g.image(resource);
        const auto px = img.downloadRGBA32F(ctx());
        const float v = px[0];
        for (uint32_t y = 0; y < img.height(); ++y)
            for (uint32_t x = 0; x < img.width(); ++x) {
                const float* p = &px[(size_t(y) * img.width() + x) * 4];
                EXPECT_EQ(p[0], v) << resource << " not uniform at " << x << "," << y;
                if (v >= 0.0f) {  // a real previous frame: the stamp of this very pixel
                    EXPECT_EQ(p[1], float(x)) << resource;
                    EXPECT_EQ(p[2], float(y)) << resource;
                }
            }
        return v;
    }
    using Seen = std::pair<float, float>;
};

}  // namespace

TEST_F(PassHistory, FillsFrameByFrameAndRotates) {
    RenderGraph g(ctx(), registry());
    g.build(stampGraph(), sized(16, 8));
    EXPECT_EQ(frame(g), Seen(-1, -1));  // first frame: nothing kept yet
    EXPECT_EQ(frame(g), Seen(0, -1));   // one frame back exists, two do not
    EXPECT_EQ(frame(g), Seen(1, 0));
    EXPECT_EQ(frame(g), Seen(2, 1));
    EXPECT_EQ(frame(g), Seen(3, 2));
}

TEST_F(PassHistory, CameraCutAndResetInvalidate) {
    RenderGraph g(ctx(), registry());
    g.build(stampGraph(), sized(16, 8));
    frame(g);
    frame(g);
    scene::FrameCamera cut;
    cut.cut = true;
    g.setCamera(cut);
    EXPECT_EQ(frame(g), Seen(-1, -1));  // frame 2 starts a new shot
    scene::FrameCamera next;
    g.setCamera(next);
    EXPECT_EQ(frame(g), Seen(2, -1));
    EXPECT_EQ(frame(g), Seen(3, 2));
    g.reset();
    EXPECT_EQ(frame(g), Seen(-1, -1));
    EXPECT_EQ(frame(g), Seen(5, -1));
}

TEST_F(PassHistory, ResizeInvalidates) {
    RenderGraph g(ctx(), registry());
    g.build(stampGraph(), sized(16, 8));
    frame(g);
    frame(g);
    g.resize(8, 8);
    EXPECT_EQ(frame(g), Seen(-1, -1));
    EXPECT_EQ(frame(g), Seen(2, -1));
}

TEST_F(PassHistory, RebuildKeepsHistoryUnlessTheFieldChanges) {
    RenderGraph g(ctx(), registry());
    g.build(stampGraph(), sized(16, 8));
    frame(g);
    frame(g);
    // A parameter that leaves the field's name, size, format and ring alone (what `--set` or the
    // inspector's live edit does): the kept frames stay valid and hold the old stamps.
    g.build(stampGraph(R"({ "stampOffset": 100 })"), sized(16, 8));
    EXPECT_EQ(frame(g), Seen(1, 0));
    EXPECT_EQ(frame(g), Seen(102, 1));
    // Fewer kept frames = another ring: a fresh one, invalid until it has held a frame.
    g.build(stampGraph(R"({ "keep": 1 })"), sized(16, 8));
    EXPECT_EQ(frame(g), Seen(-1, -1));
    EXPECT_EQ(frame(g), Seen(4, -1));
}

TEST_F(PassHistory, PreviousFramesAreNotTransientMemory) {
    RenderGraph g(ctx(), registry());
    g.build(stampGraph(), sized(16, 8));
    const uint64_t image = 16ull * 8 * 16;
    EXPECT_EQ(g.plan().historyBytes(), 2 * image);
    EXPECT_GE(g.allocatedPersistentBytes(), 5 * image);  // 3 stamp slots + seen1 + seen2
}
