// `fovea inspect`: the graph inspector (editor/, docs/inspector.md). This file owns what editor/
// must not know about: command-line options, the scene and its camera path, --set overrides.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <numeric>
#include <optional>

#include "apps/fovea/CliChecks.h"
#include "apps/fovea/Commands.h"
#include "core/graph/PassRegistry.h"
#include "core/image/ImageIO.h"
#include "core/util/Error.h"
#include "core/vk/Context.h"
#include "editor/Inspector.h"
#include "editor/VulkanWindow.h"
#include "eval/run/GraphRunner.h"

namespace fovea::app {

void addInspectCommand(CLI::App& app, InspectOptions& o) {
    auto* cmd = app.add_subcommand("inspect",
                                   "run a graph in a window: graph, previews, timings, "
                                   "live parameters (docs/inspector.md)");
    cmd->add_option("graph", o.graph.graph, "graph file (JSON); reloaded when it changes")
        ->required()
        ->check(userPath());
    cmd->add_option("--size", o.graph.size, "render size WIDTHxHEIGHT (default: graph or 256x256)");
    cmd->add_option("--set", o.graph.sets, "override a parameter: pass.param=value (repeatable)");
    cmd->add_option("--frames", o.frames, "run N frames, then exit (default: until closed)")
        ->check(CLI::Range(1, 1000000));
    cmd->add_option("--screenshot", o.screenshot,
                    "after the last frame write the whole window as PNG (+ FILE.json: where the "
                    "preview and nodes are); needs --frames");
    cmd->add_option("--script", o.script, "scripted actions per frame (docs/inspector.md)");
    cmd->add_option("--reference", o.reference,
                    "image (EXR, PNG) to compare the preview with: shown beside it, with a "
                    "difference view")
        ->check(userPath());
    cmd->add_option("--window", o.window, "window size WIDTHxHEIGHT (default 960x600)");
    cmd->add_option("--seed", o.seed, "random seed (default: graph default or 0)")
        ->check(CLI::Range(int64_t(0), std::numeric_limits<int64_t>::max()));
    cmd->add_option("--device", o.device, "GPU index or name substring (default: best available)");
    cmd->add_flag("--validation", o.validation, "enable the Vulkan validation layer");
    cmd->add_flag("--no-aliasing", o.graph.noAliasing, "give every transient image its own memory");
    cmd->add_flag("--overwrite", o.overwrite,
                  "allow screenshots and script 'saveas' to replace existing files");
    cmd->add_flag("--quiet", o.quiet, "no messages on stderr but errors");
    addSceneOptions(*cmd, o.scene);
}

namespace {

class InspectSession : public editor::GraphSession {
public:
    InspectSession(gpu::Context& ctx, RunScene& scene, const graph::GraphDesc& desc,
                   const graph::CompileOptions& options, uint64_t seed, const GraphOptions& cli)
        : mCtx(ctx),
          mScene(scene),
          mDesc(desc),
          mOptions(options),
          mCli(cli),
          mGraph(ctx, graph::passRegistry()) {
        mGraph.setScene(scene.gpu());
        mGraph.setCamera(scene.frameCamera(0, options.width, options.height));
        mGraph.build(desc, options);
        mGraph.setSeed(seed);
    }
    gpu::Context& gpu() override { return mCtx; }
    graph::RenderGraph& graph() override { return mGraph; }
    const graph::GraphDesc& desc() const override { return mDesc; }
    const graph::CompileOptions& compileOptions() const override { return mOptions; }
    bool stereo() const override { return mScene.stereo(); }
    bool hasScene() const override { return mScene.hasScene(); }
    scene::CameraDesc pathCamera() override { return mScene.cameraAt(mFrames); }

    graph::FrameTiming runFrame(const editor::FrameRequest& request) override {
        if (mFrames > 0 || request.camera) {
            scene::FrameCamera camera =
                mScene.frameCamera(mFrames, mOptions.width, mOptions.height,
                                   request.camera ? &*request.camera : nullptr);
            if (request.gaze)
                for (uint32_t e = 0; e < camera.eyeCount; ++e)
                    camera.eyes[e].gaze = (*request.gaze)[e];
            mGraph.setCamera(camera);
        }
        ++mFrames;
        return mGraph.runFrame();
    }

    graph::RenderGraph::UpdateResult update(const graph::GraphDesc& desc) override {
        try {
            auto result = mGraph.update(desc);
            mDesc = desc;
            return result;
        } catch (...) {
            if (!mGraph.built()) mGraph.build(mDesc, mOptions);  // an in-place failure keeps it
            throw;
        }
    }

    void rebuild(const graph::GraphDesc& desc) override {
        try {
            mGraph.build(desc, mOptions);
            mDesc = desc;
        } catch (...) {
            mGraph.build(mDesc, mOptions);
            throw;
        }
    }

    graph::GraphDesc loadGraphFile(const std::string& path) override {
        GraphOptions options = mCli;
        options.graph = path;
        return loadGraph(options);
    }

private:
    gpu::Context& mCtx;
    RunScene& mScene;
    graph::GraphDesc mDesc;
    graph::CompileOptions mOptions;
    GraphOptions mCli;
    graph::RenderGraph mGraph;
    uint64_t mFrames = 0;
};

double mean(const std::vector<editor::InspectorTimes>& times, double editor::InspectorTimes::*m) {
    if (times.size() <= 1) return 0.0;
    // Frame 0 compiles the UI pipeline and uploads fonts lazily: it is left out of the mean.
    double sum = 0;
    for (size_t i = 1; i < times.size(); ++i) sum += times[i].*m;
    return sum / double(times.size() - 1);
}

}  // namespace

int inspectCommand(const InspectOptions& o) {
    graph::GraphDesc desc = loadGraph(o.graph);
    auto [width, height] = renderSize(o.graph, desc);
    auto [windowWidth, windowHeight] = parseSize(o.window, "--window");
    if (!o.screenshot.empty() && o.frames == 0)
        throw InputError("--screenshot", "",
                         "needs --frames N (the screenshot is taken after "
                         "the last frame)");
    const uint64_t seed = o.seed >= 0 ? uint64_t(o.seed) : desc.defaults.seed.value_or(0);
    editor::InspectorOptions options;
    options.graphFile = o.graph.graph;
    options.frames = uint32_t(o.frames);
    options.screenshot = o.screenshot;
    options.quiet = o.quiet;
    options.overwrite = o.overwrite;
    if (!o.script.empty()) options.script = editor::parseInspectorScript(o.script);
    if (!o.reference.empty()) {
        options.referenceFile = o.reference;
        options.reference = image::readImage(o.reference);  // InputError naming the file
    }
    // Screenshots and saved graphs never replace a file silently.
    std::vector<std::pair<std::string, std::string>> files;  // path, what asked for it
    if (!o.screenshot.empty()) files.emplace_back(o.screenshot, "--screenshot");
    if (!o.screenshot.empty()) files.emplace_back(o.screenshot + ".json", "--screenshot");
    for (const auto& cmd : options.script) {
        if (cmd.verb == "screenshot") files.emplace_back(cmd.args[0] + ".json", cmd.where);
        if (cmd.verb == "screenshot" || cmd.verb == "saveas" || cmd.verb == "previewshot")
            files.emplace_back(cmd.args[0], cmd.where);
    }
    for (const auto& [file, source] : files)
        if (std::filesystem::exists(file) && !o.overwrite)
            throw InputError(source, "", "'" + file + "' exists; pass --overwrite to replace it");
    options.ignoreMouse = !o.script.empty() || !o.screenshot.empty();
    // Destruction runs in reverse: the scene's GPU buffers and the window go before the device,
    // the device before glfwTerminate. Both are created only after every input was checked.
    std::optional<editor::WindowSystem> windows;
    std::optional<gpu::Context> device;
    RunScene scene(o.scene, desc);
    windows.emplace();  // throws RuntimeError (exit 1) without a display
    gpu::ContextOptions contextOptions;
    contextOptions.device = o.device;
    contextOptions.validation = o.validation;
    contextOptions.instanceExtensions = windows->requiredInstanceExtensions();
    contextOptions.swapchain = true;
    gpu::Context& ctx = device.emplace(contextOptions);
    if (!o.quiet)
        std::cerr << "fovea: device " << ctx.deviceName() << " (" << ctx.driverName() << ")\n";
    uploadScene(ctx, scene, o.quiet);
    graph::CompileOptions compile;
    compile.width = width;
    compile.height = height;
    compile.aliasing = !o.graph.noAliasing;
    compile.sceneFeatures = scene.features();
    InspectSession session(ctx, scene, desc, compile, seed, o.graph);
    uint32_t frames = 0;
    std::vector<editor::InspectorTimes> times;
    uint64_t previewBytes = 0, windowBytes = 0;
    {
        editor::VulkanWindow window(ctx, windowWidth, windowHeight,
                                    "fovea inspect " + o.graph.graph);
        editor::Inspector inspector(session, window, options);
        frames = inspector.run();
        times = inspector.times();
        previewBytes = inspector.previewCpuBytes();
        windowBytes = window.bufferBytes();
    }
    if (!o.quiet) {
        using T = editor::InspectorTimes;
        std::cerr << "fovea: inspect: " << frames << " frames; mean CPU wall ms per frame after "
                  << "the first: graph " << mean(times, &T::graph) << ", preview "
                  << mean(times, &T::preview) << ", UI " << mean(times, &T::ui) << ", present "
                  << mean(times, &T::present) << "\n";
        std::cerr << "fovea: inspect: preview memory: CPU " << previewBytes
                  << " bytes (field copies + display bytes), host-visible buffers " << windowBytes
                  << " bytes (preview staging + screenshot read-back)\n";
        if (!o.screenshot.empty()) std::cerr << "fovea: wrote " << o.screenshot << "\n";
    }
    checkValidation(ctx);
    return kExitOk;
}

}  // namespace fovea::app
