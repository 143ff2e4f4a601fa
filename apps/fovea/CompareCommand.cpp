// `fovea compare TEST REFERENCE`: every error metric of eval/metrics/ImageMetrics.h and ꟻLIP
// (eval/flip/Flip.h), as a text table or JSON (docs/metrics.md). Unreadable files, size
// mismatches and NaN/Inf values are input errors (exit 2) naming the file.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "apps/fovea/CliChecks.h"
#include "apps/fovea/Commands.h"
#include "core/util/Error.h"
#include "eval/flip/Flip.h"
#include "eval/metrics/ImageMetrics.h"

namespace fovea::app {

namespace fs = std::filesystem;

void addCompareCommand(CLI::App& app, CompareOptions& o) {
    auto* cmd = app.add_subcommand(
        "compare",
        "error metrics of an image against a reference (RMSE, relMSE, PSNR, SSIM, ꟻLIP, ...)");
    cmd->add_option("test", o.test,
                    "image to evaluate (EXR, or PNG, JPEG, HDR, ...: core/image/ImageIO.h)")
        ->required()
        ->check(userPath());
    cmd->add_option("reference", o.reference, "reference image of the same size")
        ->required()
        ->check(userPath());
    cmd->add_flag("--json", o.json, "print the metrics as one JSON object");
    cmd->add_option("--peak", o.peak, "signal peak for PSNR and SSIM (default 1 = [0,1] images)")
        ->check(finitePositive());
    cmd->add_option("--epsilon", o.epsilon, "relMSE epsilon: (x-y)^2 / (y^2 + epsilon)")
        ->check(finitePositive());
    auto* only = cmd->add_flag("--flip", o.flipOnly, "report only ꟻLIP");
    auto* none = cmd->add_flag("--no-flip", o.noFlip, "skip ꟻLIP (the slowest metric)");
    only->excludes(none);
    cmd->add_option("--flip-mode", o.flipMode,
                    "LDR-ꟻLIP (display-encoded sRGB images) or HDR-ꟻLIP (linear); auto: HDR "
                    "for an .exr/.hdr reference, LDR otherwise")
        ->check(CLI::IsMember({"auto", "ldr", "hdr"}))
        ->excludes(none);
    cmd->add_option("--ppd", o.ppd,
                    "ꟻLIP's pixels per degree of visual angle (default 67.02: a 0.7 m wide 4K "
                    "monitor seen from 0.7 m)")
        ->check(finitePositive())
        ->excludes(none);
    cmd->add_option("--start-exposure", o.startExposure,
                    "HDR-ꟻLIP's first exposure in stops (default: from the reference)")
        ->check(finiteRange(-1000, 1000))
        ->excludes(none);
    cmd->add_option("--stop-exposure", o.stopExposure,
                    "HDR-ꟻLIP's last exposure in stops (default: from the reference)")
        ->check(finiteRange(-1000, 1000))
        ->excludes(none);
    cmd->add_option("--flip-map", o.flipMap,
                    "write the per-pixel ꟻLIP error as a grey image (.exr: the values; .png: "
                    "value * 255)")
        ->check(userPath())
        ->excludes(none);
    cmd->add_flag("--overwrite", o.overwrite, "let --flip-map replace an existing file");
}

namespace {

// The map's file: .exr or .png, in a folder that exists, not an existing file unless
// --overwrite (nothing the user has is replaced without asking). Checked before any work.
void checkFlipMapPath(const CompareOptions& o) {
    if (o.flipMap.empty()) return;
    const fs::path path(o.flipMap);
    const std::string ext = path.extension().string();
    if (ext != ".exr" && ext != ".png")
        throw InputError("--flip-map", "",
                         o.flipMap + ": expected a file name ending in .exr or .png");
    const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
        throw InputError("--flip-map", "",
                         o.flipMap + ": folder '" + folder.string() + "' does not exist");
    if (fs::exists(path, ec) && !o.overwrite)
        throw InputError("--flip-map", "", o.flipMap + ": exists; pass --overwrite to replace it");
    if (fs::exists(path, ec) && !fs::is_regular_file(path, ec))
        throw InputError("--flip-map", "", o.flipMap + ": exists and is not a regular file");
}

eval::FlipOptions flipOptionsOf(const CompareOptions& o) {
    eval::FlipOptions f;
    f.mode = o.flipMode == "auto"  ? eval::flipModeForFile(o.reference)
             : o.flipMode == "ldr" ? eval::FlipMode::Ldr
                                   : eval::FlipMode::Hdr;
    f.pixelsPerDegree = o.ppd;
    if (f.mode == eval::FlipMode::Ldr && (o.startExposure || o.stopExposure))
        throw InputError(o.startExposure ? "--start-exposure" : "--stop-exposure", "",
                         "exposures apply to HDR-ꟻLIP only, and ꟻLIP is LDR here (" +
                             std::string(o.flipMode == "auto" ? "the reference is not .exr/.hdr; "
                                                                "pass --flip-mode hdr"
                                                              : "--flip-mode ldr") +
                             ")");
    f.startExposure = o.startExposure;
    f.stopExposure = o.stopExposure;
    return f;
}

void printLine(const char* name, double value, const std::string& note) {
    char text[160];
    std::snprintf(text, sizeof text, "%-16s %14.8g  ", name, value);
    std::cout << text << note << "\n";
}

}  // namespace

int compareCommand(const CompareOptions& o) {
    eval::MetricOptions options;
    options.peak = o.peak;
    options.relMseEpsilon = o.epsilon;
    checkFlipMapPath(o);
    const std::optional<eval::FlipOptions> flipOptions =
        o.noFlip ? std::nullopt : std::optional(flipOptionsOf(o));
    // Headers first: images of different sizes are refused before either is decoded.
    const image::ImageSize testSize = image::readImageSize(o.test);  // the test image first
    eval::checkSameSize(testSize, image::readImageSize(o.reference), o.test, o.reference);
    const image::ImageRGBA test = image::readImage(o.test);
    const image::ImageRGBA reference = image::readImage(o.reference);
    eval::ImageMetrics m = eval::computeMetrics(test, reference, options, o.test, o.reference);
    std::optional<eval::FlipResult> flip;
    if (flipOptions) {
        flip = eval::computeFlip(test, reference, *flipOptions, o.test, o.reference);
        m.flipMean = flip->mean;
        if (!o.flipMap.empty()) {
            const image::ImageRGBA map = eval::flipMapImage(*flip);
            if (fs::path(o.flipMap).extension() == ".exr")
                image::writeExr(o.flipMap, map);
            else
                image::writePng(o.flipMap, map, image::PngEncoding::AsIs);
        }
    }
    if (o.json) {
        nlohmann::json j = {
            {"test", o.test}, {"reference", o.reference}, {"size", {m.width, m.height}}};
        if (o.flipOnly)
            j["flip_mean"] = m.flipMean;
        else
            j.update(eval::metricsToJson(m, options));
        if (flip) j["flip"] = eval::flipSettingsToJson(*flip);
        if (flip && !o.flipMap.empty()) j["flip"]["map"] = o.flipMap;
        std::cout << j.dump(2) << "\n";
        return kExitOk;
    }
    std::cout << "test:      " << o.test << " (" << m.width << "x" << m.height << ")\n"
              << "reference: " << o.reference << "\n";
    if (!o.flipOnly) {
        printLine("MSE", m.mse, "mean over pixels and RGB");
        printLine("RMSE", m.rmse, "sqrt(MSE)");
        printLine("RMSE %", m.rmsePercent, "100 * RMSE / peak (Peres et al. 2023 Table 4)");
        printLine("relMSE", m.relMse, "(x-y)^2 / (y^2 + eps), eps as --epsilon");
        printLine("PSNR (dB)", m.psnr, "10 log10(peak^2 / MSE); inf = identical");
        printLine("SSIM", m.ssim, "Wang et al. 2004, mean of R, G, B");
        printLine("temporal error", m.meanAbsLuminanceDiff,
                  "mean |Y(test) - Y(reference)|, Schied et al. 2017 (for consecutive frames)");
    }
    if (flip) {
        char note[160];
        if (flip->mode == eval::FlipMode::Hdr)
            std::snprintf(note, sizeof note, "HDR-ꟻLIP mean, %.2f ppd, exposures %.4f to %.4f (%u)",
                          flip->pixelsPerDegree, flip->startExposure, flip->stopExposure,
                          flip->exposureCount);
        else
            std::snprintf(note, sizeof note, "LDR-ꟻLIP mean, %.2f ppd", flip->pixelsPerDegree);
        printLine("FLIP", flip->mean, note);
        if (!o.flipMap.empty()) std::cout << "ꟻLIP map:  " << o.flipMap << "\n";
    }
    return kExitOk;
}

}  // namespace fovea::app
