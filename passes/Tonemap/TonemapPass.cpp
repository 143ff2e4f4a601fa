#include "passes/Tonemap/TonemapPass.h"

#include <cmath>

#include "core/vk/ComputePipeline.h"

namespace fovea::passes {

namespace {
const std::vector<std::string> kOperators = {"clamp", "reinhard", "aces"};
}

void TonemapPass::params(graph::ParamVisitor& v) {
    v.add("exposure", mExposure, 0.0f, "exposure in stops: colour is scaled by 2^exposure",
          {-20, 20});
    v.add("operator", mOperator, "clamp",
          "clamp: min(x,1); reinhard: x/(1+x); aces: Narkowicz's ACES filmic fit", kOperators);
    v.add("srgb", mSrgb, true, "encode with the sRGB transfer function (else linear 8-bit)");
}

void TonemapPass::reflect(graph::Reflection& r) const {
    r.input("color").floatOnly().doc("linear HDR colour, any float or unorm format");
    r.output("ldr", vk::Format::eR8G8B8A8Unorm).sameAs("color").doc("display colour");
}

void TonemapPass::compile(graph::CompileContext& ctx) {
    mPipeline = ctx.createPipeline("tonemap/tonemap.comp");
}

void TonemapPass::execute(graph::ExecuteContext& ctx) {
    const auto& out = ctx.image("ldr");
    int op = int(std::find(kOperators.begin(), kOperators.end(), mOperator) - kOperators.begin());
    ctx.bindFields(*mPipeline);
    mPipeline->set("size", glm::ivec2(out.width(), out.height()))
        .set("exposureScale", std::exp2(mExposure))
        .set("op", op)
        .set("srgb", int(mSrgb));
    ctx.dispatch(*mPipeline, out.width(), out.height());
}

}  // namespace fovea::passes
