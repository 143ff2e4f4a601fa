#include "InvertPass.h"

void InvertPass::params(fovea::graph::ParamVisitor& v) {
    v.add("white", mWhite, 1.0f, "the value inverted against: result = white - color", {0.0, 1e6});
}

void InvertPass::reflect(fovea::graph::Reflection& r) const {
    r.input("color").floatOnly().doc("the image to invert");
    r.output("result", vk::Format::eR32G32B32A32Sfloat).sameAs("color").doc("white - color");
}

void InvertPass::compile(fovea::graph::CompileContext& ctx) {
    // An absolute path: the pass's shader lives beside it, not in fovea's shader folder.
    mPipeline = ctx.createPipeline((mShaderDir / "invert" / "invert.comp").string());
}

void InvertPass::execute(fovea::graph::ExecuteContext& ctx) {
    const auto& out = ctx.image("result");
    ctx.bindFields(*mPipeline);
    mPipeline->set("size", glm::ivec2(out.width(), out.height())).set("white", mWhite);
    ctx.dispatch(*mPipeline, out.width(), out.height());
}
