// What `run`, `reference` and `bench` share: opening the device, building one graph on it with a
// scene, and running its frames (camera per frame, timings, reading outputs back). Each command
// adds its own outputs around this loop (files, report.json, errors against a reference).
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "core/graph/RenderGraph.h"
#include "core/image/ImageIO.h"
#include "eval/report/Report.h"
#include "eval/run/SceneSetup.h"

namespace fovea::gpu {
class Context;
}

namespace fovea::eval {

// Creates the device (after every input was checked, so bad input fails without one), prints
// its name unless quiet.
gpu::Context& openDevice(std::optional<gpu::Context>& device, const std::string& selector,
                         bool validation, bool quiet);
// Prints the scene's load warnings unless quiet, and uploads it.
void uploadScene(gpu::Context& ctx, RunScene& scene, bool quiet);
// Throws RuntimeError when the validation layer reported anything during the run.
void checkValidation(const gpu::Context& ctx);

struct GraphRunConfig {
    uint32_t width = 0, height = 0;
    uint64_t seed = 0;
    bool aliasing = true;
    // Set: every frame uses the camera of this camera-path frame (a converged reference of one
    // frame of a moving path); unset: frame f uses the path's frame f.
    std::optional<uint64_t> fixedCameraFrame;
    // The graph's index of the first frame (RenderGraph::setFirstFrameIndex): a reference shard
    // renders frames [firstFrame, ...) of the single run's sample streams.
    uint64_t firstFrame = 0;
};

class GraphRunner {
public:
    // Builds `desc` on `ctx` for `scene` (uploaded already; both must outlive the runner).
    GraphRunner(gpu::Context& ctx, RunScene& scene, const graph::GraphDesc& desc,
                const GraphRunConfig& config);

    // Runs the next frame (hands the graph its camera first) and returns its timings.
    graph::FrameTiming runFrame();
    uint32_t framesRun() const { return mFrames; }

    // True when the pass producing `resource` ("pass.field") survived culling.
    bool alive(const std::string& resource) const;
    // The current content of a live resource as RGBA float.
    image::ImageRGBA download(const std::string& resource) const;
    // The first marked output of the graph file whose image is a float format (not 8-bit UNORM,
    // not uint) and whose pass is alive; "" when there is none.
    std::string firstFloatOutput() const;
    // True when `resource` is an 8-bit UNORM image: display-encoded values (e.g. Tonemap's ldr,
    // sRGB applied), which ꟻLIP evaluates as LDR.
    bool displayEncoded(const std::string& resource) const;

    graph::RenderGraph& graph() { return mGraph; }
    const graph::RenderGraph& graph() const { return mGraph; }
    double buildMs() const { return mBuildMs; }
    // report.json fields that do not depend on the frames: device, scene, size, seed, build.
    ReportInputs reportBase(const std::string& graphFile, uint32_t frames) const;

private:
    gpu::Context& mCtx;
    RunScene& mScene;
    graph::GraphDesc mDesc;
    GraphRunConfig mConfig;
    graph::RenderGraph mGraph;
    double mBuildMs = 0;
    uint32_t mFrames = 0;
};

}  // namespace fovea::eval

namespace fovea::eval {

// The output compared with a reference: `requested` (must be one of the graph's marked outputs,
// alive) or, when empty, the first float output. Errors name `option`.
std::string selectComparedOutput(const GraphRunner& runner, const std::string& requested,
                                 const std::string& option);

}  // namespace fovea::eval
