#include "eval/reference/ReferenceRender.h"

#include "core/util/Error.h"
#include "eval/reference/ReferenceErrors.h"
#include "eval/run/Progress.h"

namespace fovea::eval {

uint32_t referenceSamplesPerFrame(const graph::GraphDesc& desc, const std::string& graphFile) {
    uint32_t perFrame = 0;
    for (const auto& p : desc.passes) {
        // The pass reports its samples per frame from its parameters as loaded (Pass::facts).
        const std::optional<uint32_t> spp = passFactsOf(p, graphFile).samplesPerFrame;
        if (!spp) continue;
        if (perFrame != 0 && *spp != perFrame)
            throw InputError(graphFile, "/passes",
                             "reference graphs need one samples-per-frame count; path tracing "
                             "passes disagree");
        perFrame = *spp;
    }
    if (perFrame == 0)
        throw InputError(graphFile, "/passes",
                         "a reference graph needs a path tracing pass (e.g. PathTrace)");
    return perFrame;
}

uint32_t referenceFrames(uint32_t spp, uint32_t samplesPerFrame) {
    return uint32_t((uint64_t(spp) + samplesPerFrame - 1) / samplesPerFrame);  // >= 1
}

image::ImageRGBA renderReferenceImage(gpu::Context& ctx, RunScene& scene,
                                      const graph::GraphDesc& desc, const std::string& graphFile,
                                      uint32_t spp, const GraphRunConfig& config,
                                      const std::string& output, const std::string& outputOption,
                                      bool quiet) {
    const uint32_t perFrame = referenceSamplesPerFrame(desc, graphFile);
    const uint32_t frames = referenceFrames(spp, perFrame);
    GraphRunner runner(ctx, scene, desc, config);
    const std::string compared = selectComparedOutput(runner, output, outputOption);
    Progress progress(frames, perFrame, quiet);
    for (uint32_t f = 0; f < frames; ++f) {
        runner.runFrame();
        progress.update(f + 1);
    }
    progress.finish();
    return runner.download(compared);
}

}  // namespace fovea::eval
