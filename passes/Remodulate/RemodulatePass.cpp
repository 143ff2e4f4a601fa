#include "passes/Remodulate/RemodulatePass.h"

#include "core/vk/ComputePipeline.h"

namespace fovea::passes {

void RemodulatePass::params(graph::ParamVisitor& v) {
    v.add("albedoEpsilon", mAlbedoEpsilon, 1e-3f,
          "albedo channels at or below this are treated as 1 (not divided, not multiplied); must "
          "equal the demodulating pass's rule (PathTrace uses 1e-3)",
          {0.0, 1.0});
}

void RemodulatePass::reflect(graph::Reflection& r) const {
    r.input("color").floatOnly().doc("demodulated radiance (e.g. a denoiser's output); a is kept");
    r.input("albedo").sameAs("color").floatOnly().doc("first-hit albedo (GBuffer `albedo`)");
    r.input("emission")
        .sameAs("color")
        .optional()
        .floatOnly()
        .doc("primary-hit emission added back (GBuffer `emission`); open = none");
    r.output("result", vk::Format::eR32G32B32A32Sfloat)
        .sameAs("color")
        .doc(
            "color.rgb * albedo' + emission, albedo' = albedo > albedoEpsilon ? albedo : 1 per "
            "channel; a = color.a");
}

void RemodulatePass::compile(graph::CompileContext& ctx) {
    mPipeline = ctx.createPipeline("remodulate/remodulate.comp");
}

void RemodulatePass::execute(graph::ExecuteContext& ctx) {
    const auto& out = ctx.image("result");
    ctx.bindFields(*mPipeline);
    mPipeline->set("size", glm::ivec2(out.width(), out.height()))
        .set("albedoEpsilon", mAlbedoEpsilon)
        .set("useEmission", int(ctx.connected("emission")));
    ctx.dispatch(*mPipeline, out.width(), out.height());
}

}  // namespace fovea::passes
