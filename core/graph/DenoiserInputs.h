// One vocabulary of denoiser inputs (the role NRD's ResourceType plays): the G-buffer, path
// tracer and Visual-Polar inputs that the denoisers read, each declared here once with its name,
// format rule, size rule and meaning. A denoiser picks the inputs it reads and adds only what it
// does with one (`detail`), so BMFR, SVGF and TAA cannot drift apart on what `motion` means.
#pragma once
#include <string>

#include "core/graph/Pass.h"
#include "core/graph/Reflection.h"

namespace fovea::graph {

enum class DenoiserInput {
    Color,        // `color`: noisy albedo-demodulated radiance, a = samples; any size, the others
                  // follow it (the screen, or a Visual-Polar grid: seed 003 P5 §3.3)
    Position,     // `position`: world position, w > 0 on a hit
    Normal,       // `normal`: shading normal
    Depth,        // `depth`: linear view depth, 0 = miss
    Albedo,       // `albedo` (optional): remodulation albedo; open = 1
    Emission,     // `emission` (optional): emission added back after remodulation; open = 0
    Motion,       // `motion` (optional): previous pixel - current pixel; open = camera reprojection
    VisualPolar,  // `vp` (optional): VisualPolarWarp's parameter block (also read by the G-buffer
                  // and Unwarp, which are not denoisers but share the mapping)
};

// The field name of `input` ("color", ..., "vp").
const char* denoiserInputName(DenoiserInput input);

// Declares `input` on `r` with the shared format, size rule, optionality and doc; `detail`, when
// given, is appended to the doc (what this pass does with it). Returns the builder for more
// flags (e.g. `.required()` where the pass cannot run without an optional one).
FieldBuilder declareDenoiserInput(Reflection& r, DenoiserInput input,
                                  const std::string& detail = "");

// The check every reader of `vp` shares (seed 003 P5 §3.3: history in the Visual-Polar grid
// comes from GBuffer's VP motion, not from screen reprojection): a connected `vp` needs `motion`.
void validateVisualPolarInputs(const ValidateContext& ctx);

}  // namespace fovea::graph
