// `fovea run`: compile a graph, run N frames headless, write marked outputs and report.json.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "apps/fovea/CliChecks.h"
#include "apps/fovea/Commands.h"
#include "core/image/ImageIO.h"
#include "core/scene/ViewProbe.h"
#include "core/util/Error.h"
#include "core/vk/Context.h"
#include "core/vk/Formats.h"
#include "core/vk/Resources.h"
#include "eval/reference/ReferenceErrors.h"
#include "eval/report/OutputFolder.h"
#include "eval/report/Report.h"
#include "eval/run/GraphRunner.h"
#include "eval/run/Progress.h"

namespace fovea::app {

namespace fs = std::filesystem;

void addRunCommand(CLI::App& app, RunOptions& o) {
    auto* cmd = app.add_subcommand("run", "run a graph headless and write its outputs + report");
    cmd->add_option("graph", o.graph.graph, "graph file (JSON)")->required()->check(userPath());
    cmd->add_option("--frames", o.frames, "number of frames (default: graph default or 1)")
        ->check(CLI::Range(1, std::numeric_limits<int>::max()));  // 0 is the "default" marker
    cmd->add_option("--size", o.graph.size, "render size WIDTHxHEIGHT (default: graph or 256x256)")
        ->check(nonEmptyValue());
    cmd->add_option("--out", o.out, "output directory (default: out/<graph name>)")
        ->check(nonEmptyValue())
        ->check(userPath());
    cmd->add_option("--set", o.graph.sets, "override a parameter: pass.param=value (repeatable)");
    cmd->add_option("--seed", o.seed, "random seed (default: graph default or 0)")
        ->check(nonNegativeInt64());  // -1: "default"
    cmd->add_option("--save-frames", o.saveFrames,
                    "frames whose outputs are written: 'last', 'all', 'none' or a list '0,3,7'");
    cmd->add_option("--device", o.device, "GPU index or name substring (default: best available)")
        ->check(nonEmptyValue());
    cmd->add_flag("--validation", o.validation, "enable the Vulkan validation layer");
    cmd->add_flag("--no-aliasing", o.graph.noAliasing, "give every transient image its own memory");
    cmd->add_flag("--profile-dispatches", o.profileDispatches,
                  "time every dispatch of every pass (report.json dispatch_gpu_ms; the "
                  "timestamps between dispatches can slow the frame)");
    cmd->add_flag("--overwrite", o.overwrite, "allow writing into a non-empty output directory");
    cmd->add_flag("--quiet", o.quiet, "no progress on stderr");
    cmd->add_option("--reference", o.reference,
                    "reference EXR (all frames) or directory of per-frame EXRs (*frameNNNN*.exr): "
                    "per-frame errors go into report.json")
        ->check(nonEmptyValue())
        ->check(userPath());
    cmd->add_option("--reference-noise", o.referenceNoise,
                    "second reference with another seed (file, directory or %04d pattern, as "
                    "--reference): report.json gets the reference's noise floor next to the errors")
        ->check(nonEmptyValue());
    cmd->add_option("--reference-output", o.referenceOutput,
                    "graph output compared with --reference (default: the first float output)")
        ->check(nonEmptyValue());
    auto* noFlip = cmd->add_flag("--no-flip", o.noFlip, "with --reference: skip ꟻLIP");
    cmd->add_option("--flip-mode", o.flipMode,
                    "with --reference: LDR- or HDR-ꟻLIP; auto: LDR for an 8-bit output "
                    "(display-encoded), HDR otherwise")
        ->check(CLI::IsMember({"auto", "ldr", "hdr"}))
        ->excludes(noFlip);
    cmd->add_option("--flip-ppd", o.flipPpd,
                    "with --reference: ꟻLIP's pixels per degree, a number or 'camera' (each "
                    "frame's camera, an HMD's view; default 67.02, a 4K monitor at 0.7 m)")
        ->check(CLI::Validator(
            [](std::string& v) {
                FlipChoice c;
                return parseFlipPpd(v, c)
                           ? std::string()
                           : "expected 'camera' or a finite number > 0, got '" + v + "'";
            },
            "PPD"))
        ->excludes(noFlip);
    addSceneOptions(*cmd, o.scene);
}

namespace {

// --no-flip, --flip-mode and --flip-ppd as a FlipChoice; each needs --reference.
FlipChoice flipChoiceOf(const RunOptions& o) {
    if (o.reference.empty() && (o.noFlip || o.flipMode != "auto" || !o.flipPpd.empty()))
        throw InputError(
            o.noFlip ? "--no-flip" : (o.flipMode != "auto" ? "--flip-mode" : "--flip-ppd"), "",
            "needs --reference");
    FlipChoice flip;
    flip.enabled = !o.noFlip;
    flip.mode = o.flipMode;
    if (!o.flipPpd.empty()) parseFlipPpd(o.flipPpd, flip);  // checked by the option's validator
    return flip;
}

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

// SIGINT/SIGTERM during the frames: finish the frame and its writes, then write report.json with
// "finished": false and exit 1. A second signal kills at once (the default action).
volatile std::sig_atomic_t gInterruptSignal = 0;

extern "C" void onInterrupt(int signal) {
    gInterruptSignal = signal;
    std::signal(signal, SIG_DFL);
}

// Restores the previous handlers when the frames are over.
class InterruptGuard {
public:
    InterruptGuard() {
        gInterruptSignal = 0;
        mInt = std::signal(SIGINT, onInterrupt);
        mTerm = std::signal(SIGTERM, onInterrupt);
    }
    ~InterruptGuard() {
        std::signal(SIGINT, mInt);
        std::signal(SIGTERM, mTerm);
    }
    int signal() const { return gInterruptSignal; }

private:
    void (*mInt)(int) = SIG_DFL;
    void (*mTerm)(int) = SIG_DFL;
};

bool allBlack(const image::ImageRGBA& img) {
    for (size_t i = 0; i + 3 < img.pixels.size(); i += 4)
        if (img.pixels[i] != 0.0f || img.pixels[i + 1] != 0.0f || img.pixels[i + 2] != 0.0f)
            return false;
    return true;
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

namespace {

// report.json "primary_rays" and its warnings: a CPU trace of 32x32 primary rays through the
// last frame's camera (core/scene/ViewProbe.h), between frames, so the GPU-timed frames do not
// pay for it. Catches a camera that sees no geometry or sits inside it, whatever the graph.
void addViewProbe(nlohmann::json& report, const RunScene& runScene,
                  const scene::FrameCamera& camera, uint32_t frame) {
    const std::optional<scene::ViewProbe> probe = runScene.probeView(camera);
    if (!probe) return;
    report["primary_rays"] = {{"frame", frame},
                              {"probe_rays", probe->rays},
                              {"hit_fraction", probe->hitFraction()},
                              {"inside_fraction", probe->insideFraction()},
                              {"back_face_hits", probe->backFaces},
                              {"near_hits", probe->near}};
    auto warn = [&](const std::string& warning) {
        report["warnings"].push_back(warning);
        std::cerr << "fovea: warning: " << warning << "\n";
    };
    char percent[32];
    if (probe->hitFraction() < 0.01) {
        std::snprintf(percent, sizeof percent, "%.1f%%", 100.0 * probe->hitFraction());
        warn(std::string("primary rays hit geometry in ") + percent + " of the image (" +
             std::to_string(probe->hits) + " of " + std::to_string(probe->rays) +
             " probe rays, frame " + std::to_string(frame) +
             "): the camera sees no geometry (--camera frame frames the scene)");
    }
    if (probe->looksInside()) {
        std::snprintf(percent, sizeof percent, "%.0f%%", 100.0 * probe->insideFraction());
        warn(std::string("the camera looks inside geometry: ") + percent +
             " of the primary rays first hit the back of a single-sided surface or a surface "
             "closer than 0.1% of the scene's size (frame " +
             std::to_string(frame) + "; --camera frame frames the scene)");
    }
}

}  // namespace

namespace {

// `run --reference` (and --reference-noise): the references, the compared output and the
// per-frame errors against each, as one step of the run.
class ReferenceComparison {
public:
    // Checks the options and the reference files (every frame present, right size) before
    // any device is opened.
    ReferenceComparison(const RunOptions& o, uint32_t width, uint32_t height, uint32_t frames)
        : mOptions(o) {
        if (!o.referenceOutput.empty() && o.reference.empty())
            throw InputError("--reference-output", "", "needs --reference");
        if (!o.referenceNoise.empty() && o.reference.empty())
            throw InputError("--reference-noise", "", "needs --reference");
        mFlip = flipChoiceOf(o);
        if (!o.reference.empty()) {
            mTruth.emplace(o.reference, "--reference", width, height);
            mTruth->requireFrames(0, frames - 1);
        }
        if (!o.referenceNoise.empty()) {
            mNoise.emplace(o.referenceNoise, "--reference-noise", width, height);
            mNoise->requireFrames(0, frames - 1);
        }
    }
    // Picks the compared output of the built graph; errors per foveation layer when it has some.
    void attach(GraphRunner& runner, const std::optional<eval::LayerRadii>& layers) {
        if (layers) {
            mErrors.setLayers(*layers);
            mFloor.setLayers(*layers);
        }
        if (!mTruth) return;  // reading the output back costs a transfer: only with --reference
        mCompared = selectComparedOutput(runner, mOptions.referenceOutput, "--reference-output");
        mTruth->choose(mCompared);
        if (mNoise) mNoise->choose(mCompared);
        mErrors.setFlip(mFlip, runner.displayEncoded(mCompared));
        mFloor.setFlip(mFlip, runner.displayEncoded(mCompared));
    }
    void add(uint32_t f, GraphRunner& runner) {
        if (!mTruth) return;
        const auto* camera = &runner.graph().camera();
        mErrors.add(f, runner.download(mCompared), mCompared + " frame " + std::to_string(f),
                    mTruth->forFrame(f), mTruth->fileFor(f).string(), camera);
        if (mNoise)
            mFloor.add(f, mNoise->forFrame(f), mNoise->fileFor(f).string(), mTruth->forFrame(f),
                       mTruth->fileFor(f).string(), camera);
    }
    // report.json "reference" (null without --reference).
    nlohmann::json json() const {
        if (!mTruth) return nullptr;
        nlohmann::json j = mErrors.json();
        j["path"] = mOptions.reference;
        j["mode"] = mTruth->perFrame() ? "per-frame" : "single";
        j["output"] = mCompared;
        if (mNoise) {
            j["noise_floor"] = mFloor.json();
            j["noise_floor"]["path"] = mOptions.referenceNoise;
            // docs/report-format.md: the error against the truth once the reference's own
            // noise (half the floor's MSE) is taken out; 0 = within the reference's noise.
            j["mean"]["rmse_noise_corrected"] =
                eval::noiseCorrectedRmse(mErrors.mean().mse, mFloor.mean().mse);
        }
        return j;
    }

private:
    const RunOptions& mOptions;
    FlipChoice mFlip{};
    std::optional<ReferenceSource> mTruth, mNoise;
    std::string mCompared;
    FrameErrors mErrors, mFloor;
};

// Writes frame f's marked outputs (EXR + PNG) and keeps, per output, whether the last saved
// frame was black in every pixel: a camera that sees no geometry or no light gives such an
// image with exit 0, which must not pass unnoticed.
void saveFrameOutputs(const OutputFolder& folder, GraphRunner& runner, const graph::GraphDesc& desc,
                      uint32_t f, uint32_t frames, ReportInputs& report,
                      std::map<std::string, uint32_t>& blackOutputs) {
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
        folder.write(base + ".exr", [&](const fs::path& path) { image::writeExr(path, img); });
        // An 8-bit UNORM output (e.g. Tonemap's) is display-encoded already.
        const bool displayEncoded = gpu::formatIsUnorm8(runner.graph().image(name).format());
        folder.write(base + ".png", [&](const fs::path& path) {
            image::writePng(path, img,
                            displayEncoded ? image::PngEncoding::AsIs : image::PngEncoding::Srgb);
        });
        report.outputs.push_back(base + ".exr");
        report.outputs.push_back(base + ".png");
        if (allBlack(img))
            blackOutputs[name] = f;
        else
            blackOutputs.erase(name);
    }
}

// report.json with the run's warnings, written last: its presence and "finished" say whether
// the folder is complete.
void writeRunReport(const OutputFolder& folder, GraphRunner& runner, const RunScene& scene,
                    const ReportInputs& report, const std::map<std::string, uint32_t>& blackOutputs,
                    uint32_t framesDone, uint32_t frames) {
    nlohmann::json json = buildReport(runner.graph(), report);
    json["warnings"] = nlohmann::json::array();
    for (const auto& [name, frame] : blackOutputs) {
        const std::string warning =
            "output '" + name + "' is black in every pixel (frame " + std::to_string(frame) +
            "): the camera may see no geometry or no light (--camera frame frames the scene)";
        json["warnings"].push_back(warning);
        std::cerr << "fovea: warning: " << warning << "\n";
    }
    if (framesDone > 0) addViewProbe(json, scene, runner.graph().camera(), framesDone - 1);
    json["finished"] = framesDone == frames;
    json["frames_run"] = framesDone;
    folder.writeText("report.json", json.dump(2) + "\n");
}

}  // namespace

int runCommand(const RunOptions& o) {
    // 1. Every input is checked before a device is opened: bad input fails fast, without one.
    graph::GraphDesc desc = loadGraph(o.graph);
    auto [width, height] = renderSize(o.graph, desc);
    if (o.frames < 0) throw InputError("--frames", "", "must be at least 1");
    const uint32_t frames = o.frames > 0 ? uint32_t(o.frames) : desc.defaults.frames.value_or(1);
    const uint64_t seed = o.seed >= 0 ? uint64_t(o.seed) : desc.defaults.seed.value_or(0);
    // The device outlives the scene's GPU buffers (declared first, destroyed last).
    std::optional<gpu::Context> device;
    RunScene scene(o.scene, desc);
    const std::set<uint32_t> save = parseSaveFrames(o.saveFrames, frames);
    scene.checkRenderSize(width, height);
    // The graph's free-text name must not pick a folder outside out/ ("../x", "/abs").
    const fs::path outDir =
        o.out.empty() ? fs::path("out") / safeFolderName(desc.name) : fs::path(o.out);
    checkOutputDir(outDir, "--out", o.overwrite);
    ReferenceComparison comparison(o, width, height, frames);

    // 2. Device, scene and graph.
    gpu::Context& ctx = openDevice(device, o.device, o.validation, o.quiet);
    uploadScene(ctx, scene, o.quiet);
    GraphRunner runner(ctx, scene, desc,
                       {width, height, seed, !o.graph.noAliasing, o.fixedCameraFrame});
    runner.graph().setDispatchProfiling(o.profileDispatches);
    comparison.attach(runner, foveationRadiiOf(desc));
    const OutputFolder folder(outDir, "--out", o.overwrite);
    InterruptGuard interrupt;

    // 3. The frames: timings, errors against the references, saved outputs.
    ReportInputs report = runner.reportBase(o.graph.graph, frames);
    Progress progress(frames, o.samplesPerFrame, o.quiet);
    uint32_t framesDone = 0;
    std::map<std::string, uint32_t> blackOutputs;
    for (uint32_t f = 0; f < frames && !interrupt.signal(); ++f) {
        graph::FrameTiming t = runner.runFrame();
        report.frameGpuMs.push_back(t.gpuMs);
        report.frameCpuMs.push_back(t.recordCpuMs);
        report.overheadCpuMs.push_back(t.recordCpuMs - t.passCpuMs);
        comparison.add(f, runner);
        if (save.count(f)) saveFrameOutputs(folder, runner, desc, f, frames, report, blackOutputs);
        progress.update(f + 1);
        framesDone = f + 1;
    }
    progress.finish();
    checkValidation(ctx);

    // 4. The report, last.
    report.reference = comparison.json();
    writeRunReport(folder, runner, scene, report, blackOutputs, framesDone, frames);
    if (interrupt.signal()) {
        std::cerr << "error: interrupted (signal " << interrupt.signal() << ") after " << framesDone
                  << " of " << frames << " frames; " << (outDir / "report.json").string()
                  << " says \"finished\": false\n";
        return kExitRuntime;
    }
    if (!o.quiet) std::cerr << "fovea: wrote " << (outDir / "report.json").string() << "\n";
    return kExitOk;
}

}  // namespace fovea::app
