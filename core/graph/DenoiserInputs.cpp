#include "core/graph/DenoiserInputs.h"

#include "core/sampling/VisualPolar.h"

namespace fovea::graph {

const char* denoiserInputName(DenoiserInput input) {
    switch (input) {
        case DenoiserInput::Color:
            return "color";
        case DenoiserInput::Position:
            return "position";
        case DenoiserInput::Normal:
            return "normal";
        case DenoiserInput::Depth:
            return "depth";
        case DenoiserInput::Albedo:
            return "albedo";
        case DenoiserInput::Emission:
            return "emission";
        case DenoiserInput::Motion:
            return "motion";
        case DenoiserInput::VisualPolar:
            return "vp";
    }
    return "?";
}

FieldBuilder declareDenoiserInput(Reflection& r, DenoiserInput input, const std::string& detail) {
    const char* name = denoiserInputName(input);
    auto withDetail = [&](const std::string& doc) {
        return detail.empty() ? doc : doc + "; " + detail;
    };
    if (input == DenoiserInput::VisualPolar) {
        FieldBuilder b = r.input(name).buffer(sampling::kVisualPolarParamsBytes).optional();
        return b.doc(
            withDetail("VisualPolarWarp's `vp` block: the Visual-Polar mapping (P5 §3.3)"));
    }
    FieldBuilder b = r.input(name).floatOnly();
    if (input == DenoiserInput::Color) {
        b.anySize().doc(withDetail(
            "noisy albedo-demodulated radiance (PathTrace `demodulated`), a = samples (0 = "
            "none)"));
        return b;
    }
    b.sameAs("color");
    switch (input) {
        case DenoiserInput::Position:
            return b.doc(withDetail("world position, w > 0 on a hit"));
        case DenoiserInput::Normal:
            return b.doc(withDetail("shading normal (unit length)"));
        case DenoiserInput::Depth:
            return b.doc(withDetail("linear view depth, 0 = miss (GBuffer `depth`)"));
        case DenoiserInput::Albedo:
            return b.optional().doc(withDetail("remodulation albedo; open: 1"));
        case DenoiserInput::Emission:
            return b.optional().doc(withDetail("emission added back after remodulation; open: 0"));
        case DenoiserInput::Motion:
            return b.optional().doc(withDetail(
                "previous pixel - current pixel (GBuffer `motion`); open: reproject positions "
                "through the camera"));
        default:
            return b;
    }
}

void validateVisualPolarInputs(const ValidateContext& ctx) {
    if (ctx.connected("vp") && !ctx.connected("motion"))
        ctx.fail("vp", "a Visual-Polar image needs the input 'motion' (GBuffer VP motion)");
}

}  // namespace fovea::graph
