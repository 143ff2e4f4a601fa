// `fovea run`: compile a graph, run N frames headless, write marked outputs and report.json.
#include <chrono>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>

#include "apps/fovea/Commands.h"
#include "apps/fovea/Progress.h"
#include "apps/fovea/Report.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/image/ImageIO.h"
#include "core/util/Error.h"
#include "core/vk/Context.h"
#include "core/vk/Formats.h"
#include "core/vk/Resources.h"

namespace fovea::app {

namespace fs = std::filesystem;

void addRunCommand(CLI::App& app, RunOptions& o) {
    auto* cmd = app.add_subcommand("run", "run a graph headless and write its outputs + report");
    cmd->add_option("graph", o.graph.graph, "graph file (JSON)")->required();
    cmd->add_option("--frames", o.frames, "number of frames (default: graph default or 1)")
        ->check(CLI::Range(1, std::numeric_limits<int>::max()));  // 0 is the "default" marker
    cmd->add_option("--size", o.graph.size, "render size WIDTHxHEIGHT (default: graph or 256x256)");
    cmd->add_option("--out", o.out, "output directory (default: out/<graph name>)");
    cmd->add_option("--set", o.graph.sets, "override a parameter: pass.param=value (repeatable)");
    cmd->add_option("--seed", o.seed, "random seed (default: graph default or 0)")
        ->check(CLI::Range(int64_t(0), std::numeric_limits<int64_t>::max()));  // -1: "default"
    cmd->add_option("--save-frames", o.saveFrames,
                    "frames whose outputs are written: 'last', 'all', 'none' or a list '0,3,7'");
    cmd->add_option("--device", o.device, "GPU index or name substring (default: best available)");
    cmd->add_flag("--validation", o.validation, "enable the Vulkan validation layer");
    cmd->add_flag("--no-aliasing", o.graph.noAliasing, "give every transient image its own memory");
    cmd->add_flag("--overwrite", o.overwrite, "allow writing into a non-empty output directory");
    cmd->add_flag("--quiet", o.quiet, "no progress on stderr");
    addSceneOptions(*cmd, o.scene);
}

namespace {

std::set<uint32_t> parseSaveFrames(const std::string& text, uint32_t frames) {
    std::set<uint32_t> out;
    if (text.empty())
        throw InputError("--save-frames", "",
                         "expected 'last', 'all', 'none' or a comma list "
                         "of frame numbers, got ''");
    if (text == "none") return out;
    if (text == "last") return {frames - 1};
    if (text == "all") {
        for (uint32_t f = 0; f < frames; ++f) out.insert(f);
        return out;
    }
    if (text.back() == ',')
        throw InputError("--save-frames", "", "trailing comma in '" + text + "'");
    std::stringstream s(text);
    std::string item;
    while (std::getline(s, item, ',')) {
        char* end = nullptr;
        unsigned long f = std::strtoul(item.c_str(), &end, 10);
        if (item.empty() || *end != '\0')
            throw InputError("--save-frames", "",
                             "expected 'last', 'all', 'none' or a comma "
                             "list of frame numbers, got '" +
                                 text + "'");
        if (f >= frames)
            throw InputError(
                "--save-frames", "",
                "frame " + item + " is not run (--frames " + std::to_string(frames) + ")");
        out.insert(uint32_t(f));
    }
    return out;
}

image::ImageRGBA download(const gpu::Context& ctx, const gpu::Image& img) {
    return {img.width(), img.height(), img.downloadRGBA32F(ctx)};
}

}  // namespace

int runCommand(const RunOptions& o) {
    graph::GraphDesc desc = loadGraph(o.graph);
    auto [width, height] = renderSize(o.graph, desc);
    if (o.frames < 0) throw InputError("--frames", "", "must be at least 1");
    uint32_t frames = o.frames > 0 ? uint32_t(o.frames) : desc.defaults.frames.value_or(1);
    uint64_t seed = o.seed >= 0 ? uint64_t(o.seed) : desc.defaults.seed.value_or(0);
    // The device outlives the scene's GPU buffers (declared first, destroyed last), but is
    // created only after every input was checked: bad input fails fast, without a device.
    std::optional<gpu::Context> device;
    RunScene scene(o.scene, desc);
    std::set<uint32_t> save = parseSaveFrames(o.saveFrames, frames);
    fs::path outDir =
        o.out.empty() ? fs::path("out") / (desc.name.empty() ? "run" : desc.name) : fs::path(o.out);
    if (fs::exists(outDir) && !fs::is_directory(outDir))
        throw InputError("--out", "", "'" + outDir.string() + "' exists and is not a directory");
    if (fs::exists(outDir) && !fs::is_empty(outDir) && !o.overwrite)
        throw InputError("--out", "",
                         "directory '" + outDir.string() +
                             "' is not empty; pass --overwrite to replace its files");

    gpu::ContextOptions ctxOptions;
    ctxOptions.device = o.device;
    ctxOptions.validation = o.validation;
    gpu::Context& ctx = device.emplace(ctxOptions);
    if (!o.quiet)
        std::cerr << "fovea: device " << ctx.deviceName() << " (" << ctx.driverName() << " "
                  << ctx.driverInfo() << ")\n";

    for (const auto& w : scene.hasScene() ? scene.json()["warnings"] : nlohmann::json::array())
        if (!o.quiet) std::cerr << "fovea: warning: " << w.get<std::string>() << "\n";
    scene.upload(ctx);

    graph::CompileOptions options;
    options.width = width;
    options.height = height;
    options.aliasing = !o.graph.noAliasing;
    options.sceneFeatures = scene.features();
    graph::RenderGraph graph(ctx, graph::passRegistry());
    graph.setScene(scene.gpu());
    graph.setCamera(scene.frameCamera(0, width, height));
    auto buildStart = std::chrono::steady_clock::now();
    graph.build(desc, options);
    const double buildMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - buildStart)
            .count();
    graph.setSeed(seed);
    fs::create_directories(outDir);

    ReportInputs report;
    report.graphFile = o.graph.graph;
    report.scene = scene.json();
    report.buildMs = buildMs;
    report.deviceName = ctx.deviceName();
    report.driver = ctx.driverName() + " " + ctx.driverInfo();
    report.width = width;
    report.height = height;
    report.frames = frames;
    report.seed = seed;
    Progress progress(frames, o.samplesPerFrame, o.quiet);
    for (uint32_t f = 0; f < frames; ++f) {
        if (f > 0) graph.setCamera(scene.frameCamera(f, width, height));
        graph::FrameTiming t = graph.runFrame();
        report.frameGpuMs.push_back(t.gpuMs);
        report.frameCpuMs.push_back(t.recordCpuMs);
        report.overheadCpuMs.push_back(t.recordCpuMs - t.passCpuMs);
        if (save.count(f)) {
            for (const auto& out : desc.outputs) {
                const auto& plan = graph.plan();
                if (!plan.nodes[plan.findNode(out.source.pass)].alive) continue;  // culled
                std::string base = out.source.str();
                if (frames > 1) {
                    char suffix[32];
                    std::snprintf(suffix, sizeof suffix, ".frame%04u", f);
                    base += suffix;
                }
                image::ImageRGBA img = download(ctx, graph.image(out.source.str()));
                image::writeExr(outDir / (base + ".exr"), img);
                // An 8-bit UNORM output (e.g. Tonemap's) is display-encoded already.
                const bool displayEncoded =
                    gpu::formatIsUnorm8(graph.image(out.source.str()).format());
                image::writePng(
                    outDir / (base + ".png"), img,
                    displayEncoded ? image::PngEncoding::AsIs : image::PngEncoding::Srgb);
                report.outputs.push_back(base + ".exr");
                report.outputs.push_back(base + ".png");
            }
        }
        progress.update(f + 1);
    }
    progress.finish();
    if (ctx.validationMessageCount() > 0)
        throw RuntimeError(std::to_string(ctx.validationMessageCount()) +
                           " Vulkan validation message(s) during the run (see above)");
    std::ofstream(outDir / "report.json") << buildReport(graph, report).dump(2) << "\n";
    if (!o.quiet) std::cerr << "fovea: wrote " << (outDir / "report.json").string() << "\n";
    return kExitOk;
}

}  // namespace fovea::app
