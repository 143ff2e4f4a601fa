#include "passes/Blit/BlitPass.h"

#include "core/vk/ComputePipeline.h"
#include "core/vk/Formats.h"

namespace fovea::passes {

namespace {
// The shader stores through a float image2D: integer formats (r32ui, ...) cannot be written, so
// they are not offered (a graph naming one fails at compile, listing these choices).
std::vector<std::string> writableFormats() {
    std::vector<std::string> out;
    for (const std::string& name : gpu::formatNames())
        if (!gpu::formatIsUint(gpu::parseFormat(name))) out.push_back(name);
    return out;
}
}  // namespace

void BlitPass::params(graph::ParamVisitor& v) {
    v.add("scale", mScale, 1.0f, "output size = render size * scale (rounded up)", {1.0 / 64, 64});
    v.add("format", mFormat, "rgba32f", "output format (float or unorm)", writableFormats());
    v.add("filter", mFilter, "linear", "resampling filter", {"nearest", "linear"});
    v.add("activeEvery", mActiveEvery, 1,
          "run on every N-th frame only; on the others copy the input through (bypass)",
          {1, 1 << 20});
}

void BlitPass::reflect(graph::Reflection& r) const {
    r.input("color").floatOnly().doc("image to resample");
    r.output("result", gpu::parseFormat(mFormat)).scaled(mScale).doc("resampled image");
}

void BlitPass::compile(graph::CompileContext& ctx) {
    mPipeline = ctx.createPipeline("blit/blit.comp");
}

bool BlitPass::isActive(const graph::FrameInfo& frame) const {
    return mActiveEvery <= 1 || frame.index % uint64_t(mActiveEvery) == 0;
}

std::vector<std::pair<std::string, std::string>> BlitPass::bypass() const {
    if (mActiveEvery <= 1) return {};
    return {{"color", "result"}};
}

void BlitPass::execute(graph::ExecuteContext& ctx) {
    const auto& out = ctx.image("result");
    ctx.bindFields(*mPipeline);
    mPipeline->set("size", glm::ivec2(out.width(), out.height()))
        .set("linear", int(mFilter == "linear"));
    ctx.dispatch(*mPipeline, out.width(), out.height());
}

}  // namespace fovea::passes
