// `fovea run`: compile a graph, run N frames headless, write marked outputs and report.json.
#include <chrono>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <set>
#include <sstream>

#include "apps/fovea/Commands.h"
#include "apps/fovea/GraphRunner.h"
#include "apps/fovea/Progress.h"
#include "apps/fovea/ReferenceErrors.h"
#include "apps/fovea/Report.h"
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
    cmd->add_option("--reference", o.reference,
                    "reference EXR (all frames) or directory of per-frame EXRs (*frameNNNN*.exr): "
                    "per-frame errors go into report.json");
    cmd->add_option("--reference-output", o.referenceOutput,
                    "graph output compared with --reference (default: the first float output)");
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

}  // namespace

void checkOutputDir(const fs::path& dir, const std::string& option, bool overwrite) {
    if (fs::exists(dir) && !fs::is_directory(dir))
        throw InputError(option, "", "'" + dir.string() + "' exists and is not a directory");
    if (fs::exists(dir) && !fs::is_empty(dir) && !overwrite)
        throw InputError(
            option, "",
            "directory '" + dir.string() + "' is not empty; pass --overwrite to replace its files");
}

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
    checkOutputDir(outDir, "--out", o.overwrite);
    if (!o.referenceOutput.empty() && o.reference.empty())
        throw InputError("--reference-output", "", "needs --reference");
    std::optional<ReferenceSource> reference;
    if (!o.reference.empty()) {
        reference.emplace(o.reference, "--reference", width, height);
        reference->requireFrames(0, frames - 1);
    }

    gpu::Context& ctx = openDevice(device, o.device, o.validation, o.quiet);
    uploadScene(ctx, scene, o.quiet);
    GraphRunner runner(ctx, scene, desc, {width, height, seed, !o.graph.noAliasing, {}});
    // Reading the compared output back costs a transfer per frame: only with --reference.
    const std::string compared =
        reference ? selectComparedOutput(runner, o.referenceOutput, "--reference-output") : "";
    if (reference) reference->choose(compared);
    FrameErrors errors;
    fs::create_directories(outDir);

    ReportInputs report = runner.reportBase(o.graph.graph, frames);
    Progress progress(frames, o.samplesPerFrame, o.quiet);
    for (uint32_t f = 0; f < frames; ++f) {
        graph::FrameTiming t = runner.runFrame();
        report.frameGpuMs.push_back(t.gpuMs);
        report.frameCpuMs.push_back(t.recordCpuMs);
        report.overheadCpuMs.push_back(t.recordCpuMs - t.passCpuMs);
        if (reference)
            errors.add(f, runner.download(compared), compared + " frame " + std::to_string(f),
                       reference->forFrame(f), reference->fileFor(f).string(),
                       &runner.graph().camera());
        if (save.count(f)) {
            for (const auto& out : desc.outputs) {
                const std::string name = out.source.str();
                if (!runner.alive(name)) continue;  // culled
                std::string base = name;
                if (frames > 1) {
                    char suffix[32];
                    std::snprintf(suffix, sizeof suffix, ".frame%04u", f);
                    base += suffix;
                }
                image::ImageRGBA img = runner.download(name);
                image::writeExr(outDir / (base + ".exr"), img);
                // An 8-bit UNORM output (e.g. Tonemap's) is display-encoded already.
                const bool displayEncoded =
                    gpu::formatIsUnorm8(runner.graph().image(name).format());
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
    checkValidation(ctx);
    if (reference) {
        report.reference = errors.json();
        report.reference["path"] = o.reference;
        report.reference["mode"] = reference->perFrame() ? "per-frame" : "single";
        report.reference["output"] = compared;
    }
    std::ofstream(outDir / "report.json") << buildReport(runner.graph(), report).dump(2) << "\n";
    if (!o.quiet) std::cerr << "fovea: wrote " << (outDir / "report.json").string() << "\n";
    return kExitOk;
}

}  // namespace fovea::app
