#include "tests/graph/GoldenHarness.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/scene/Camera.h"
#include "core/scene/CameraPath.h"
#include "core/scene/SceneGpu.h"
#include "core/scene/SceneLoader.h"
#include "core/vk/Context.h"
#include "core/vk/Formats.h"
#include "core/vk/Resources.h"
#include "passes/RegisterPasses.h"

namespace fovea::test {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path repositoryRoot() {
    return fs::path(FOVEA_TEST_DIR).parent_path();
}
fs::path defaultGoldenRoot() {
    return fs::path(FOVEA_TEST_DIR) / "goldens";
}
fs::path defaultFailureRoot() {
    return fs::current_path() / "golden-failures";
}

GoldenTolerance defaultTolerance(const std::string& formatName) {
    uint32_t bytesPerChannel = 4;
    try {
        vk::Format format = gpu::parseFormat(formatName);
        if (!gpu::formatIsUint(format))
            bytesPerChannel = gpu::formatBytesPerPixel(format) / gpu::formatChannels(format);
    } catch (const std::exception&) {
        // a format without a fovea name: treat it as float
    }
    // 8-bit unorm (e.g. Tonemap's rgba8): a value next to a rounding boundary may flip by one
    // code (1/255 ~ 0.0039) on another device or compiler. Allow one code (not two: 0.0078), on
    // a few percent of the channels only (rmse 1e-3 ~ 6% of the channels one code off).
    if (bytesPerChannel == 1) return {.rmse = 1e-3, .maxAbs = 0.0042};
    // Half floats: one ulp is ~1e-3 for values in [1, 2).
    if (bytesPerChannel == 2) return {.rmse = 1e-4, .maxAbs = 2e-3};
    // 32-bit floats (and uints): the utility passes do exact or few-operation float math, so
    // devices differ at rounding level (~1e-7 relative); 1e-4 absolute still catches every
    // visible change.
    return {.rmse = 1e-5, .maxAbs = 1e-4};
}

GoldenMode modeFromEnvironment() {
    const char* value = std::getenv("FOVEA_UPDATE_GOLDENS");
    return value && std::string(value) == "1" ? GoldenMode::Update : GoldenMode::Compare;
}

const char* goldenStatusName(GoldenStatus s) {
    switch (s) {
        case GoldenStatus::Match:
            return "match";
        case GoldenStatus::Mismatch:
            return "MISMATCH";
        case GoldenStatus::Missing:
            return "MISSING";
        case GoldenStatus::Stale:
            return "STALE";
        case GoldenStatus::Invalid:
            return "INVALID";
        case GoldenStatus::Written:
            return "written";
        case GoldenStatus::Unchanged:
            return "unchanged";
    }
    return "?";
}

bool GoldenReport::ok() const {
    for (const auto& o : outputs)
        if (o.status != GoldenStatus::Match && o.status != GoldenStatus::Written &&
            o.status != GoldenStatus::Unchanged)
            return false;
    return !outputs.empty();
}

std::string GoldenReport::summary() const {
    std::string text;
    if (outputs.empty()) text = "golden: the graph produced no outputs\n";
    for (const auto& o : outputs) text += o.message + "\n";
    return text;
}

namespace {

fs::path resolveGraph(const fs::path& graph) {
    return graph.is_absolute() ? graph : repositoryRoot() / graph;
}

std::string formatNumber(double v) {
    std::ostringstream s;
    s << std::setprecision(3) << v;
    return s.str();
}

std::string nowUtc() {
    std::time_t t = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&t, &tm);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return text;
}

// "FOVEA_UPDATE_GOLDENS=1 /path/fovea_tests --gtest_filter=Suite.Test"
std::string updateCommand() {
    std::error_code error;
    fs::path exe = fs::read_symlink("/proc/self/exe", error);
    std::string command = "FOVEA_UPDATE_GOLDENS=1 " + (error ? "fovea_tests" : exe.string());
    if (const auto* info = testing::UnitTest::GetInstance()->current_test_info())
        command += " --gtest_filter=" + std::string(info->test_suite_name()) + "." + info->name();
    return command;
}

std::optional<json> readSidecar(const fs::path& path, std::string& error) {
    std::ifstream stream(path, std::ios::binary);
    if (!stream) {
        error = "cannot read " + path.string();
        return std::nullopt;
    }
    json j = json::parse(stream, nullptr, false);
    if (j.is_discarded() || !j.is_object()) {
        error = path.string() + ": not a JSON object";
        return std::nullopt;
    }
    return j;
}

std::optional<GoldenTolerance> sidecarTolerance(const json& sidecar) {
    if (!sidecar.contains("tolerance")) return std::nullopt;
    const json& t = sidecar["tolerance"];
    if (!t.is_object() || !t.contains("rmse") || !t.contains("max_abs") || !t["rmse"].is_number() ||
        !t["max_abs"].is_number())
        return std::nullopt;
    GoldenTolerance tol{t["rmse"].get<double>(), t["max_abs"].get<double>()};
    if (!(tol.rmse >= 0) || !(tol.maxAbs >= 0)) return std::nullopt;
    return tol;
}

// The sidecar fields that must match the test for the golden to apply.
json identity(const GoldenSpec& spec, const RenderedOutput& out, uint64_t seed) {
    json id = {
        {"graph", spec.graph.generic_string()}, {"output", out.output},  {"format", out.format},
        {"size", {spec.width, spec.height}},    {"frames", spec.frames}, {"seed", seed}};
    if (!spec.scene.empty()) {
        id["scene"] = spec.scene;
        id["stereo"] = spec.stereo;
        if (!spec.cameraPath.empty()) id["camera"] = spec.cameraPath;
    }
    if (!spec.params.empty()) id["params"] = spec.params;
    return id;
}

// Names of identity fields where `sidecar` differs from `expected`, e.g. "size [64,64] (test
// runs [32,32])".
std::vector<std::string> identityDifferences(const json& sidecar, const json& expected) {
    std::vector<std::string> out;
    for (const auto& [key, value] : expected.items()) {
        if (!sidecar.contains(key))
            out.push_back("no '" + key + "'");
        else if (sidecar[key] != value)
            out.push_back(key + " " + sidecar[key].dump() + " (test runs " + value.dump() + ")");
    }
    return out;
}

bool allFinite(const image::ImageRGBA& image) {
    return std::all_of(image.pixels.begin(), image.pixels.end(),
                       [](float v) { return std::isfinite(v); });
}

bool bitIdentical(const image::ImageRGBA& a, const image::ImageRGBA& b) {
    return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(float)) == 0;
}

// |difference| scaled so its largest value is white, for looking at (the EXR holds raw values).
image::ImageRGBA normalized(image::ImageRGBA diff) {
    float peak = 0;
    for (size_t i = 0; i < diff.pixels.size(); ++i)
        if (i % 4 != 3 && std::isfinite(diff.pixels[i])) peak = std::max(peak, diff.pixels[i]);
    for (size_t i = 0; i < diff.pixels.size(); ++i)
        if (i % 4 != 3)
            diff.pixels[i] =
                std::isfinite(diff.pixels[i]) ? (peak > 0 ? diff.pixels[i] / peak : 0) : 1.0f;
    return diff;
}

// Writes <failureRoot>/<name>/<output>.actual.{exr,png}; returns the EXR path.
fs::path writeActual(const GoldenSpec& spec, const RenderedOutput& out) {
    fs::path dir = spec.failureRoot / spec.name;
    fs::create_directories(dir);
    fs::path exr = dir / (out.output + ".actual.exr");
    image::writeExr(exr, out.image);
    // An 8-bit output (Tonemap's ldr) is display-encoded already: write it as-is.
    bool encoded = gpu::formatIsUnorm8(gpu::parseFormat(out.format));
    image::writePng(dir / (out.output + ".actual.png"), out.image,
                    encoded ? image::PngEncoding::AsIs : image::PngEncoding::Srgb);
    return exr;
}

// Removes what an earlier failing run left for this output.
void clearFailure(const GoldenSpec& spec, const std::string& output) {
    std::error_code ignored;
    for (const char* suffix : {".actual.exr", ".actual.png", ".diff.exr", ".diff.png"})
        fs::remove(spec.failureRoot / spec.name / (output + suffix), ignored);
    fs::remove(spec.failureRoot / spec.name, ignored);  // only when empty (keeps the root:
    // another test process may be writing into it)
}

std::string prefix(const GoldenSpec& spec, const std::string& output) {
    return "golden " + spec.name + "/" + output + ": ";
}

GoldenOutputResult compareOutput(const GoldenSpec& spec, const RenderedOutput& out, uint64_t seed) {
    GoldenOutputResult r;
    r.output = out.output;
    const fs::path dir = spec.goldenRoot / spec.name;
    r.golden = dir / (out.output + ".exr");
    const fs::path sidecarPath = dir / (out.output + ".json");
    const std::string howTo = "\n  to create or update it (then review the images and commit " +
                              dir.string() + "/):\n    " + updateCommand();

    if (!fs::exists(r.golden) || !fs::exists(sidecarPath)) {
        r.status = GoldenStatus::Missing;
        r.actual = writeActual(spec, out);
        r.message = prefix(spec, out.output) + "MISSING: no golden " +
                    (fs::exists(r.golden) ? sidecarPath : r.golden).string() + " for graph " +
                    spec.graph.generic_string() + "\n  actual: " + r.actual.string() + howTo;
        return r;
    }
    std::string error;
    std::optional<json> sidecar = readSidecar(sidecarPath, error);
    std::optional<GoldenTolerance> tolerance;
    if (sidecar) tolerance = sidecarTolerance(*sidecar);
    if (!sidecar || !tolerance) {
        r.status = GoldenStatus::Invalid;
        r.message =
            prefix(spec, out.output) + "INVALID sidecar: " +
            (sidecar ? sidecarPath.string() + ": no valid tolerance {rmse, max_abs}" : error) +
            howTo;
        return r;
    }
    r.tolerance = *tolerance;
    std::vector<std::string> differences = identityDifferences(*sidecar, identity(spec, out, seed));
    if (!differences.empty()) {
        r.status = GoldenStatus::Stale;
        r.actual = writeActual(spec, out);
        std::string list;
        for (const auto& d : differences) list += (list.empty() ? "" : "; ") + d;
        r.message = prefix(spec, out.output) + "STALE: " + sidecarPath.string() +
                    " was made for another run: " + list + "\n  actual: " + r.actual.string() +
                    howTo;
        return r;
    }
    image::ImageRGBA golden;
    try {
        golden = image::readImage(r.golden);
    } catch (const std::exception& e) {
        r.status = GoldenStatus::Invalid;
        r.message = prefix(spec, out.output) + "INVALID golden image: " + e.what() + howTo;
        return r;
    }
    image::CompareTolerance compareTolerance{.rmse = r.tolerance.rmse,
                                             .maxAbs = r.tolerance.maxAbs,
                                             .threshold = r.tolerance.maxAbs,
                                             .maxPercentOver = 100.0};
    r.compare = image::compareImages(out.image, golden, compareTolerance.threshold);
    const std::string numbers = "rmse " + formatNumber(r.compare.rmse) + " (tolerance " +
                                formatNumber(r.tolerance.rmse) + "), max_abs " +
                                formatNumber(r.compare.maxAbs) + " (tolerance " +
                                formatNumber(r.tolerance.maxAbs) + "), " +
                                formatNumber(r.compare.percentOver) + "% of pixels over max_abs";
    if (r.compare.pass(compareTolerance)) {
        r.status = GoldenStatus::Match;
        clearFailure(spec, out.output);
        r.message = prefix(spec, out.output) + "match: " + numbers;
        return r;
    }
    r.status = GoldenStatus::Mismatch;
    r.actual = writeActual(spec, out);
    if (!r.compare.sizeMismatch) {
        image::ImageRGBA diff = image::differenceImage(out.image, golden);
        r.difference = spec.failureRoot / spec.name / (out.output + ".diff.exr");
        image::writeExr(r.difference, diff);
        image::writePng(spec.failureRoot / spec.name / (out.output + ".diff.png"),
                        normalized(diff));
    }
    r.message =
        prefix(spec, out.output) + "MISMATCH: " +
        (r.compare.sizeMismatch
             ? "size " + std::to_string(out.image.width) + "x" + std::to_string(out.image.height) +
                   ", golden " + std::to_string(golden.width) + "x" + std::to_string(golden.height)
             : numbers) +
        "\n  golden:     " + r.golden.string() + "\n  actual:     " + r.actual.string() +
        (r.difference.empty() ? std::string()
                              : "\n  difference: " + r.difference.string() +
                                    " (|actual - golden|; .diff.png is scaled to its "
                                    "maximum)") +
        "\n  if the change is intended, update the golden:\n    " + updateCommand();
    return r;
}

GoldenOutputResult updateOutput(const GoldenSpec& spec, const RenderedOutput& out, uint64_t seed,
                                const std::string& device, const std::string& driver) {
    GoldenOutputResult r;
    r.output = out.output;
    const fs::path dir = spec.goldenRoot / spec.name;
    r.golden = dir / (out.output + ".exr");
    const fs::path sidecarPath = dir / (out.output + ".json");
    if (!allFinite(out.image)) {
        r.status = GoldenStatus::Invalid;
        r.actual = writeActual(spec, out);
        r.message = prefix(spec, out.output) +
                    "INVALID: the output has NaN or infinite values; not writing a golden "
                    "(actual: " +
                    r.actual.string() + ")";
        return r;
    }
    std::string ignored;
    std::optional<json> existing =
        fs::exists(sidecarPath) ? readSidecar(sidecarPath, ignored) : std::nullopt;
    std::optional<GoldenTolerance> existingTolerance;
    if (existing) existingTolerance = sidecarTolerance(*existing);
    r.tolerance = spec.tolerance      ? *spec.tolerance
                  : existingTolerance ? *existingTolerance
                                      : defaultTolerance(out.format);
    const json id = identity(spec, out, seed);

    // Bit-identical image and the same metadata: leave both files alone (clean diffs).
    if (existing && existingTolerance && *existingTolerance == r.tolerance &&
        identityDifferences(*existing, id).empty() && fs::exists(r.golden)) {
        try {
            if (bitIdentical(image::readImage(r.golden), out.image)) {
                r.status = GoldenStatus::Unchanged;
                clearFailure(spec, out.output);
                r.message =
                    prefix(spec, out.output) + "unchanged (bit-identical): " + r.golden.string();
                return r;
            }
        } catch (const std::exception&) {
            // unreadable: rewrite it below
        }
    }
    fs::create_directories(dir);
    image::writeExr(r.golden, out.image);
    // Written in reading order (graph, output, ..., created), not json's sorted order.
    nlohmann::ordered_json sidecar;
    for (const auto& [key, value] : id.items()) sidecar[key] = value;
    sidecar["device"] = device;
    sidecar["driver"] = driver;
    sidecar["tolerance"] = {{"rmse", r.tolerance.rmse}, {"max_abs", r.tolerance.maxAbs}};
    sidecar["created"] = nowUtc();
    std::ofstream(sidecarPath, std::ios::binary) << sidecar.dump(2) << "\n";
    r.status = GoldenStatus::Written;
    clearFailure(spec, out.output);
    r.message = prefix(spec, out.output) + "wrote " + r.golden.string() + " and " +
                sidecarPath.filename().string();
    return r;
}

}  // namespace

std::vector<RenderedOutput> renderGraphOutputs(gpu::Context& ctx, const GoldenSpec& spec,
                                               uint64_t& seedUsed) {
    registerBuiltinPasses();
    graph::GraphDesc desc = graph::parseGraphFile(resolveGraph(spec.graph));
    for (const auto& [passName, values] : spec.params.items()) {
        auto pass = std::find_if(desc.passes.begin(), desc.passes.end(),
                                 [&](const graph::PassDesc& p) { return p.name == passName; });
        if (pass == desc.passes.end())
            throw std::runtime_error("golden '" + spec.name + "': no pass '" + passName + "'");
        for (const auto& [param, value] : values.items()) pass->params[param] = value;
    }
    seedUsed = spec.seed ? *spec.seed : desc.defaults.seed.value_or(0);
    graph::CompileOptions options;
    options.width = spec.width;
    options.height = spec.height;
    std::unique_ptr<scene::Scene> sceneData;
    std::unique_ptr<scene::SceneGpu> sceneGpu;
    scene::CameraRigOptions rig;
    rig.stereo = spec.stereo;
    std::optional<scene::CameraPath> path;
    if (!spec.cameraPath.empty()) {
        path = scene::CameraPath::load(repositoryRoot() / spec.cameraPath);
        rig.model = path->model().value_or(scene::CameraModel::Perspective);
    }
    if (!spec.scene.empty()) {
        const bool builtin = spec.scene.rfind("builtin:", 0) == 0;
        sceneData = std::make_unique<scene::Scene>(
            scene::loadScene(builtin ? spec.scene : (repositoryRoot() / spec.scene).string()));
        sceneGpu = std::make_unique<scene::SceneGpu>(ctx, *sceneData);
        options.sceneFeatures =
            sceneGpu->features() | (spec.stereo ? graph::kSceneStereo : 0u) |
            (rig.model == scene::CameraModel::Equirect ? graph::kSceneEquirect : 0u);
    }
    const scene::CameraDesc camera = !sceneData                   ? scene::CameraDesc{}
                                     : sceneData->cameras.empty() ? sceneData->defaultCamera()
                                                                  : sceneData->cameras.front();
    graph::RenderGraph graph(ctx, graph::passRegistry());
    graph.setScene(sceneGpu.get());
    // The camera of frame f: the path's (pose and gaze), else the scene's, still.
    std::optional<scene::FrameCamera> previous;
    auto cameraOf = [&](uint32_t f) {
        if (!path)
            return scene::makeFrameCamera(camera, spec.width, spec.height, rig, f, nullptr,
                                          nullptr);
        const scene::CameraSample sample = path->at(f);
        const auto gaze = sample.gaze.value_or(
            std::array<glm::vec2, scene::kMaxEyes>{glm::vec2(0.5f), glm::vec2(0.5f)});
        scene::FrameCamera c =
            scene::makeFrameCamera(sample.camera, spec.width, spec.height, rig, f,
                                   previous ? &*previous : nullptr, gaze.data());
        previous = c;
        return c;
    };
    graph.setCamera(cameraOf(0));
    graph.build(desc, options);
    graph.setSeed(seedUsed);
    for (uint32_t f = 0; f < spec.frames; ++f) {
        if (f > 0) graph.setCamera(cameraOf(f));
        graph.runFrame();
    }
    std::vector<RenderedOutput> outputs;
    const auto& plan = graph.plan();
    // The pass contract: every pass's GPU memory is a graph field the plan lists. A golden of a
    // pass that allocates its own would still match, so this is checked here, for every golden.
    for (size_t n = 0; n < plan.nodes.size(); ++n)
        if (const uint64_t own = graph.records()[n].allocationsOutsidePlan; own != 0)
            throw std::runtime_error(
                "pass '" + plan.nodes[n].name + "' (" + plan.nodes[n].type + ") made " +
                std::to_string(own) +
                " device allocations outside the plan (declare buffer fields)");
    for (const auto& out : desc.outputs) {
        if (!plan.nodes[plan.findNode(out.source.pass)].alive) continue;  // culled: no image
        const gpu::Image& image = graph.image(out.source.str());
        outputs.push_back({out.source.str(),
                           gpu::formatName(image.format()),
                           {image.width(), image.height(), image.downloadRGBA32F(ctx)}});
    }
    return outputs;
}

GoldenReport runGolden(gpu::Context& ctx, const GoldenSpec& spec) {
    GoldenReport report;
    report.mode = spec.mode == GoldenMode::FromEnvironment ? modeFromEnvironment() : spec.mode;
    uint64_t seed = 0;
    std::vector<RenderedOutput> outputs = renderGraphOutputs(ctx, spec, seed);
    const std::string device = ctx.deviceName();
    const std::string driver = ctx.driverName() + " " + ctx.driverInfo();

    std::set<std::string> produced;
    for (const auto& out : outputs) {
        produced.insert(out.output);
        report.outputs.push_back(report.mode == GoldenMode::Update
                                     ? updateOutput(spec, out, seed, device, driver)
                                     : compareOutput(spec, out, seed));
    }
    // Goldens of outputs the graph no longer produces (renamed, removed or culled).
    const fs::path dir = spec.goldenRoot / spec.name;
    std::vector<fs::path> orphans;
    if (fs::is_directory(dir))
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().extension() == ".exr" && !produced.count(e.path().stem().string()))
                orphans.push_back(e.path());
    std::sort(orphans.begin(), orphans.end());
    for (const auto& orphan : orphans) {
        GoldenOutputResult r;
        r.output = orphan.stem().string();
        r.golden = orphan;
        fs::path sidecar = fs::path(orphan).replace_extension(".json");
        if (report.mode == GoldenMode::Update) {
            fs::remove(orphan);
            fs::remove(sidecar);
            r.status = GoldenStatus::Written;
            r.message = prefix(spec, r.output) + "removed " + orphan.string() +
                        " (+ .json): the graph has no such output any more";
        } else {
            r.status = GoldenStatus::Stale;
            r.message = prefix(spec, r.output) + "STALE: " + orphan.string() +
                        " belongs to no output of " + spec.graph.generic_string() +
                        " (renamed, removed or culled); remove it, or run\n    " + updateCommand();
        }
        report.outputs.push_back(r);
    }
    return report;
}

::testing::AssertionResult goldenMatches(gpu::Context& ctx, const GoldenSpec& spec) {
    GoldenReport report = runGolden(ctx, spec);
    if (report.mode == GoldenMode::Update)
        std::cout << "[golden] FOVEA_UPDATE_GOLDENS=1: updating goldens instead of comparing\n"
                  << report.summary() << std::flush;
    if (report.ok()) return ::testing::AssertionSuccess() << report.summary();
    return ::testing::AssertionFailure() << "\n" << report.summary();
}

}  // namespace fovea::test
