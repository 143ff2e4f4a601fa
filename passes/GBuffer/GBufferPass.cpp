#include "passes/GBuffer/GBufferPass.h"

#include <cctype>

#include "core/graph/DenoiserInputs.h"
#include "core/sampling/VisualPolar.h"
#include "core/scene/SceneGpu.h"
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
    r.input("coords", vk::Format::eR32G32B32A32Sfloat)
        .optional()
        .floatOnly()
        .doc(
            "VisualPolarWarp coords (seed 003 P5 §3.2): trace a regular (rho, phi) grid, one "
            "primary ray per traced texel at its screen position; the outputs take its size, "
            "untraced texels get flags bit2 (clipped); open = the screen grid");
    graph::declareDenoiserInput(r, graph::DenoiserInput::VisualPolar,
                                "with coords: motion in Visual-Polar texels (previous screen "
                                "position mapped into the grid); open: motion in screen pixels");
    r.output("visibility", vk::Format::eR32G32B32A32Uint)
        .sameAs("coords")
        .doc(
            "x triangle + 1 (0 = miss), y/z barycentrics (float bits), w flags: bit0 traced, "
            "bit1 hit, bit2 clipped (Visual-Polar texel never traced), bits 8..15 eye");
    r.output("position", vk::Format::eR32G32B32A32Sfloat)
        .sameAs("coords")
        .doc("world position; w 1 = hit");
    r.output("normal", vk::Format::eR16G16B16A16Sfloat)
        .sameAs("coords")
        .doc("shading normal facing the viewer; w 1 = hit");
    r.output("depth", vk::Format::eR32Sfloat).sameAs("coords").doc("linear view depth; 0 = none");
    r.output("albedo", vk::Format::eR16G16B16A16Sfloat)
        .sameAs("coords")
        .doc("first-hit base colour (linear); a 1 = hit");
    r.output("motion", vk::Format::eR16G16Sfloat)
        .sameAs("coords")
        .doc(
            "previous pixel - current pixel (jitter-free); 0 = none. On a Visual-Polar grid with "
            "`vp`: previous texel - current texel (columns, rows of the column, phi wrapped)");
    r.output("material", vk::Format::eR32Uint).sameAs("coords").doc("material index + 1; 0 = none");
    r.output("roughness_metallic", vk::Format::eR16G16Sfloat)
        .sameAs("coords")
        .doc("x roughness, y metallic");
    r.output("emission", vk::Format::eR16G16B16A16Sfloat)
        .sameAs("coords")
        .doc(
            "radiance emitted toward the camera at the first hit; a 1 = hit. On a miss with an "
            "environment (`--env`): the environment's radiance in the ray's direction (the "
            "background), a 0");
}

void GBufferPass::validate(const graph::ValidateContext& ctx) const {
    // A Visual-Polar grid already is the sample distribution (P5 §3.2): no list on top of it.
    if (ctx.connected("coords") && ctx.connected(sampling::kSampleLayoutField))
        ctx.fail("coords", "inputs 'coords' and 'layout' cannot both be connected");
}

void GBufferPass::compile(graph::CompileContext& ctx) {
    // A scene without textures / emitters compiles those paths out (SceneGpu::defines).
    std::vector<std::pair<std::string, std::string>> defines;
    if (ctx.scene()) defines = ctx.scene()->defines();
    mStochastic = ctx.scene() && ctx.scene()->hasStochasticAlpha();
    mVariant.clear();
    for (const auto& [name, value] : defines) {
        std::string feature = name.rfind("SCENE_HAS_", 0) == 0 ? name.substr(10) : name;
        for (char& c : feature) c = char(std::tolower(static_cast<unsigned char>(c)));
        if (!mVariant.empty()) mVariant += ",";
        mVariant += (value == "0" ? "no-" : "") + feature;
    }
    mPipeline =
        ctx.createPipeline("gbuffer/gbuffer.comp", defines, {sampling::kSampleLayoutBinding});
}

void GBufferPass::execute(graph::ExecuteContext& ctx) {
    const auto& out = ctx.image("visibility");
    const bool useLayout = ctx.connected(sampling::kSampleLayoutField);
    const bool useCoords = ctx.connected("coords");
    ctx.bindFields(*mPipeline);
    ctx.bindField(*mPipeline, sampling::kSampleLayoutBinding, sampling::kSampleLayoutField);
    mPipeline->set("size", glm::uvec2(out.width(), out.height()))
        .set("useLayout", uint32_t(useLayout))
        .set("useCoords", uint32_t(useCoords))
        .set("useVp", uint32_t(useCoords && ctx.connected("vp")))
        .set("useJitter", uint32_t(mJitter));
    if (useLayout) {
        // Unlisted pixels must read invalid, never last frame's values: clear everything, then
        // trace the list. The graph only orders whole passes, so this pass orders its own two
        // dispatches (write-after-write on the same images).
        mPipeline->set("clearPass", 1u);
        ctx.dispatch(*mPipeline, out.width(), out.height());
    }
    mPipeline->set("clearPass", 0u);
    ctx.dispatch(*mPipeline, out.width(), out.height());
}

}  // namespace fovea::passes
