#include "eval/run/GraphRunner.h"

#include <algorithm>
#include <chrono>
#include <iostream>

#include "core/graph/PassRegistry.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"
#include "core/vk/Context.h"
#include "core/vk/Formats.h"
#include "core/vk/Resources.h"

namespace fovea::eval {

gpu::Context& openDevice(std::optional<gpu::Context>& device, const std::string& selector,
                         bool validation, bool quiet) {
    gpu::ContextOptions options;
    options.device = selector;
    options.validation = validation;
    gpu::Context& ctx = device.emplace(options);
    if (!quiet)
        std::cerr << "fovea: device " << ctx.deviceName() << " (" << ctx.driverName() << " "
                  << ctx.driverInfo() << ")\n";
    return ctx;
}

void uploadScene(gpu::Context& ctx, RunScene& scene, bool quiet) {
    for (const auto& w : scene.hasScene() ? scene.json()["warnings"] : nlohmann::json::array())
        if (!quiet) std::cerr << "fovea: warning: " << w.get<std::string>() << "\n";
    scene.upload(ctx);
}

void checkValidation(const gpu::Context& ctx) {
    if (ctx.validationMessageCount() > 0)
        throw RuntimeError(std::to_string(ctx.validationMessageCount()) +
                           " Vulkan validation message(s) during the run (see above)");
}

GraphRunner::GraphRunner(gpu::Context& ctx, RunScene& scene, const graph::GraphDesc& desc,
                         const GraphRunConfig& config)
    : mCtx(ctx), mScene(scene), mDesc(desc), mConfig(config), mGraph(ctx, graph::passRegistry()) {
    graph::CompileOptions options;
    options.width = config.width;
    options.height = config.height;
    options.aliasing = config.aliasing;
    options.sceneFeatures = scene.features();
    mGraph.setScene(scene.gpu());
    // Passes may size or specialize themselves from the first camera, so it is set before build.
    mGraph.setCamera(scene.frameCamera(config.fixedCameraFrame.value_or(config.firstFrame),
                                       config.width, config.height));
    mGraph.setFirstFrameIndex(config.firstFrame);
    auto start = std::chrono::steady_clock::now();
    mGraph.build(desc, options);
    mBuildMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    mGraph.setSeed(config.seed);
}

graph::FrameTiming GraphRunner::runFrame() {
    if (mFrames > 0)
        mGraph.setCamera(
            mScene.frameCamera(mConfig.fixedCameraFrame.value_or(mConfig.firstFrame + mFrames),
                               mConfig.width, mConfig.height));
    graph::FrameTiming t = mGraph.runFrame();
    ++mFrames;
    return t;
}

bool GraphRunner::alive(const std::string& resource) const {
    const auto& plan = mGraph.plan();
    const std::string pass = resource.substr(0, resource.find('.'));
    for (const auto& node : plan.nodes)
        if (node.name == pass) return node.alive;
    return false;
}

image::ImageRGBA GraphRunner::download(const std::string& resource) const {
    const gpu::Image& img = mGraph.image(resource);
    return {img.width(), img.height(), img.downloadRGBA32F(mCtx)};
}

std::string GraphRunner::firstFloatOutput() const {
    for (const auto& out : mDesc.outputs) {
        const std::string name = out.source.str();
        if (!alive(name)) continue;
        const vk::Format format = mGraph.image(name).format();
        if (!gpu::formatIsUnorm8(format) && !gpu::formatIsUint(format)) return name;
    }
    return "";
}

bool GraphRunner::displayEncoded(const std::string& resource) const {
    return gpu::formatIsUnorm8(mGraph.image(resource).format());
}

ReportInputs GraphRunner::reportBase(const std::string& graphFile, uint32_t frames) const {
    ReportInputs report;
    report.graphFile = graphFile;
    report.scene = mScene.json();
    report.buildMs = mBuildMs;
    report.deviceName = mCtx.deviceName();
    report.driver = mCtx.driverName() + " " + mCtx.driverInfo();
    report.shaderDir = mCtx.shaderCompiler().shaderRoot().string();
    report.width = mConfig.width;
    report.height = mConfig.height;
    report.frames = frames;
    report.seed = mConfig.seed;
    return report;
}

std::string selectComparedOutput(const GraphRunner& runner, const std::string& requested,
                                 const std::string& option) {
    const auto& desc = runner.graph().desc();
    std::vector<std::string> names;
    for (const auto& out : desc.outputs) names.push_back(out.source.str());
    if (requested.empty()) {
        std::string first = runner.firstFloatOutput();
        if (first.empty())
            throw InputError(option, "",
                             "graph '" + desc.file +
                                 "' has no live float output to compare; name one of its "
                                 "outputs with " +
                                 option);
        return first;
    }
    if (std::find(names.begin(), names.end(), requested) == names.end()) {
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
        throw InputError(option, "",
                         "'" + requested + "' is not an output of graph '" + desc.file + "'" +
                             didYouMean(requested, names) + " (outputs: " + list + ")");
    }
    if (!runner.alive(requested))
        throw InputError(option, "", "output '" + requested + "' is culled in this run");
    return requested;
}

}  // namespace fovea::eval
