// Test-only pass "FrameStamp": output `stamp` keeps `keep` (1 or 2) previous frames (pass-declared
// history); each frame it writes (frame index + stampOffset, x, y, 1) into `stamp` and copies what
// the graph hands it as the previous frames into `seen1` / `seen2`, or -1 where the graph says the
// history is invalid (tests/shaders/frame_stamp.comp). Used by tests/graph/HistoryTests.cpp.
#pragma once
#include <memory>
#include <string>

#include "core/graph/Pass.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"

namespace fovea::test {

// `stamp` keeps `keep` previous frames (1 or 2); `stampOffset` is added to the frame index
// written as the stamp (a parameter that changes nothing in the resources).
class FrameStampPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override {
        v.add("keep", mKeep, 2, "previous frames kept", {1, 2});
        v.add("stampOffset", mOffset, 0.0f, "added to the stamp", {0, 1e6});
    }
    void reflect(graph::Reflection& r) const override {
        const auto rgba32 = vk::Format::eR32G32B32A32Sfloat;
        r.output("stamp", rgba32).history(uint32_t(mKeep));
        r.output("seen1", rgba32);
        r.output("seen2", rgba32);
    }
    void compile(graph::CompileContext& ctx) override {
        std::string shader = FOVEA_TEST_DIR;
        shader += "/shaders/frame_stamp.comp";
        mPipeline = ctx.createPipeline(shader, {{"KEEP2", mKeep == 2 ? "1" : "0"}});
    }
    void execute(graph::ExecuteContext& ctx) override {
        const auto& out = ctx.image("stamp");
        ctx.bindFields(*mPipeline);
        mPipeline->set("size", glm::ivec2(out.width(), out.height()))
            .set("stampValue", float(ctx.frame().index) + mOffset)
            .set("valid1", int(ctx.historyValid("stamp", 1)))
            .set("valid2", int(ctx.historyValid("stamp", 2)));
        ctx.dispatch(*mPipeline, out.width(), out.height());
    }

private:
    int mKeep = 2;
    float mOffset = 0.0f;
    std::unique_ptr<gpu::ComputePipeline> mPipeline;
};

}  // namespace fovea::test
