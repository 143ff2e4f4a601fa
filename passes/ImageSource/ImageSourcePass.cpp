#include "passes/ImageSource/ImageSourcePass.h"

#include <glm/glm.hpp>

#include "core/vk/ComputePipeline.h"

namespace fovea::passes {

namespace {
const std::vector<std::string> kPatterns = {"constant", "gradient", "noise", "frame-index"};
}

void ImageSourcePass::params(graph::ParamVisitor& v) {
    v.add("pattern", mPattern, "gradient",
          "constant: 'value' everywhere; gradient: (u, v, 1-u) * value; noise: uniform [0,1) per "
          "channel from a hash of (pixel, seed) * value; frame-index: the frame number * "
          "(value, 1), so alpha is the frame number too; other patterns write alpha 1",
          kPatterns);
    v.add("value", mValue, glm::vec3(1.0f), "colour (constant) or per-channel scale (others)");
    v.add("seed", mSeed, 0,
          "noise seed: the shader's seed is seed + 7919 * run seed (--seed), plus "
          "104729 * frame index when animate (unsigned 32-bit, wrapping)",
          {0, 2147483647});
    v.add("animate", mAnimate, false, "noise: change the pattern every frame");
}

void ImageSourcePass::reflect(graph::Reflection& r) const {
    r.output("color", vk::Format::eR32G32B32A32Sfloat).screen().doc("the generated image");
}

void ImageSourcePass::compile(graph::CompileContext& ctx) {
    mPipeline = ctx.createPipeline("image_source/image_source.comp");
}

void ImageSourcePass::execute(graph::ExecuteContext& ctx) {
    const auto& frame = ctx.frame();
    int pattern = int(std::find(kPatterns.begin(), kPatterns.end(), mPattern) - kPatterns.begin());
    uint32_t seed = uint32_t(mSeed) + uint32_t(frame.seed) * 7919u;
    if (mAnimate) seed += uint32_t(frame.index) * 104729u;
    ctx.bindFields(*mPipeline);
    mPipeline->set("value", glm::vec4(mValue, 1.0f))
        .set("size", glm::ivec2(frame.width, frame.height))
        .set("pattern", pattern)
        .set("seed", seed)
        .set("frame", uint32_t(frame.index));
    ctx.dispatch(*mPipeline, frame.width, frame.height);
}

}  // namespace fovea::passes
