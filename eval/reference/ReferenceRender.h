// Converged references rendered in process (`fovea reference`, a bench's rendered reference): a
// reference graph (graphs/reference.json: PathTrace + Accumulate) accumulated for a number of
// samples per pixel with the camera held still.
#pragma once
#include <cstdint>
#include <string>

#include "core/graph/GraphDesc.h"
#include "core/image/ImageIO.h"
#include "eval/run/GraphRunner.h"

namespace fovea::eval {

// Samples per pixel per frame of a reference graph: what its enabled path tracing passes report
// (Pass::facts().samplesPerFrame, e.g. PathTrace's spp), which must agree. Errors name
// `graphFile`.
uint32_t referenceSamplesPerFrame(const graph::GraphDesc& desc, const std::string& graphFile);
// Frames a reference graph needs for `spp` samples per pixel (>= 1).
uint32_t referenceFrames(uint32_t spp, uint32_t samplesPerFrame);

// The converged reference of one camera-path frame: `desc` (a reference graph, e.g.
// graphs/reference.json) accumulated over referenceFrames(spp, ...) frames with the camera held
// at `config.fixedCameraFrame`; returns `output` (default: its first float output). What
// `fovea reference` renders, in process. Errors about the
// output name `outputOption`.
image::ImageRGBA renderReferenceImage(gpu::Context& ctx, RunScene& scene,
                                      const graph::GraphDesc& desc, const std::string& graphFile,
                                      uint32_t spp, const GraphRunConfig& config,
                                      const std::string& output, const std::string& outputOption,
                                      bool quiet);

}  // namespace fovea::eval
