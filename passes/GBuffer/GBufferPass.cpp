#include "passes/GBuffer/GBufferPass.h"

#include <cctype>

#include "core/scene/SceneGpu.h"
#include "core/vk/Barriers.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"

namespace fovea::passes {

void GBufferPass::params(graph::ParamVisitor& v) {
    v.add("jitter", mJitter, true,
          "offset primary rays by the camera's sub-pixel jitter (zero unless the run jitters)");
}

void GBufferPass::reflect(graph::Reflection& r) const {
    r.input(sampling::kSampleLayoutField)
        .buffer(sampling::kSampleLayoutHeaderBytes)
        .optional()
        .doc(
            "sample layout (docs/sample-layouts.md): only listed pixels are traced, the rest "
            "are invalid; open = every pixel");
    r.output("visibility", vk::Format::eR32G32B32A32Uint)
        .screen()
        .doc(
            "x triangle + 1 (0 = miss), y/z barycentrics (float bits), w flags: bit0 traced, "
            "bit1 hit, bits 8..15 eye");
    r.output("position", vk::Format::eR32G32B32A32Sfloat).screen().doc("world position; w 1 = hit");
    r.output("normal", vk::Format::eR16G16B16A16Sfloat)
        .screen()
        .doc("shading normal facing the viewer; w 1 = hit");
    r.output("depth", vk::Format::eR32Sfloat).screen().doc("linear view depth; 0 = none");
    r.output("albedo", vk::Format::eR16G16B16A16Sfloat)
        .screen()
        .doc("first-hit base colour (linear); a 1 = hit");
    r.output("motion", vk::Format::eR16G16Sfloat)
        .screen()
        .doc("previous pixel - current pixel (jitter-free); 0 = none");
    r.output("material", vk::Format::eR32Uint).screen().doc("material index + 1; 0 = none");
    r.output("roughness_metallic", vk::Format::eR16G16Sfloat)
        .screen()
        .doc("x roughness, y metallic");
    r.output("emission", vk::Format::eR16G16B16A16Sfloat)
        .screen()
        .doc("radiance emitted toward the camera at the first hit; a 1 = hit");
}

void GBufferPass::compile(graph::CompileContext& ctx) {
    // A scene without textures / emitters compiles those paths out (SceneGpu::defines).
    std::vector<std::pair<std::string, std::string>> defines;
    if (ctx.scene()) defines = ctx.scene()->defines();
    mVariant.clear();
    for (const auto& [name, value] : defines) {
        std::string feature = name.rfind("SCENE_HAS_", 0) == 0 ? name.substr(10) : name;
        for (char& c : feature) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (!mVariant.empty()) mVariant += ",";
        mVariant += (value == "0" ? "no-" : "") + feature;
    }
    mPipeline =
        ctx.createPipeline("gbuffer/gbuffer.comp", defines, {sampling::kSampleLayoutBinding});
    mLayoutInput = std::make_unique<sampling::SampleLayoutInput>(ctx.gpu());
}

void GBufferPass::execute(graph::ExecuteContext& ctx) {
    const auto& out = ctx.image("visibility");
    const bool useLayout = ctx.connected(sampling::kSampleLayoutField);
    ctx.bindFields(*mPipeline);
    mLayoutInput->bind(*mPipeline, useLayout ? &ctx.buffer(sampling::kSampleLayoutField) : nullptr);
    mPipeline->set("size", glm::uvec2(out.width(), out.height()))
        .set("useLayout", uint32_t(useLayout))
        .set("useJitter", uint32_t(mJitter));
    if (useLayout) {
        // Unlisted pixels must read invalid, never last frame's values: clear everything, then
        // trace the list. The graph only orders whole passes, so this pass orders its own two
        // dispatches (write-after-write on the same images).
        mPipeline->set("clearPass", 1u);
        mPipeline->dispatch(ctx.cmd(), out.width(), out.height());
        gpu::computeToComputeBarrier(ctx.cmd());
    }
    mPipeline->set("clearPass", 0u);
    mPipeline->dispatch(ctx.cmd(), out.width(), out.height());
}

}  // namespace fovea::passes
