// `fovea compare TEST REFERENCE`: every error metric of core/image/ImageMetrics.h, as a text
// table or JSON (docs/metrics.md). Unreadable files, size mismatches and NaN/Inf values are input
// errors (exit 2) naming the file.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "apps/fovea/CliChecks.h"
#include "apps/fovea/Commands.h"
#include "core/image/ImageMetrics.h"

namespace fovea::app {

void addCompareCommand(CLI::App& app, CompareOptions& o) {
    auto* cmd = app.add_subcommand(
        "compare", "error metrics of an image against a reference (RMSE, relMSE, PSNR, SSIM, ...)");
    cmd->add_option("test", o.test, "image to evaluate (EXR or any format OpenImageIO reads)")
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
}

int compareCommand(const CompareOptions& o) {
    image::MetricOptions options;
    options.peak = o.peak;
    options.relMseEpsilon = o.epsilon;
    // Headers first: images of different sizes are refused before either is decoded.
    const image::ImageSize testSize = image::readImageSize(o.test);  // the test image first
    image::checkSameSize(testSize, image::readImageSize(o.reference), o.test, o.reference);
    const image::ImageRGBA test = image::readImage(o.test);
    const image::ImageRGBA reference = image::readImage(o.reference);
    const image::ImageMetrics m =
        image::computeMetrics(test, reference, options, o.test, o.reference);
    if (o.json) {
        nlohmann::json j = {
            {"test", o.test}, {"reference", o.reference}, {"size", {m.width, m.height}}};
        j.update(image::metricsToJson(m, options));
        std::cout << j.dump(2) << "\n";
        return kExitOk;
    }
    auto line = [](const char* name, double value, const char* note) {
        char text[160];
        std::snprintf(text, sizeof text, "%-16s %14.8g  %s\n", name, value, note);
        std::cout << text;
    };
    std::cout << "test:      " << o.test << " (" << m.width << "x" << m.height << ")\n"
              << "reference: " << o.reference << "\n";
    line("MSE", m.mse, "mean over pixels and RGB");
    line("RMSE", m.rmse, "sqrt(MSE)");
    line("RMSE %", m.rmsePercent, "100 * RMSE / peak (Peres et al. 2023 Table 4)");
    line("relMSE", m.relMse, "(x-y)^2 / (y^2 + eps), eps as --epsilon");
    line("PSNR (dB)", m.psnr, "10 log10(peak^2 / MSE); inf = identical");
    line("SSIM", m.ssim, "Wang et al. 2004, mean of R, G, B");
    line("temporal error", m.meanAbsLuminanceDiff,
         "mean |Y(test) - Y(reference)|, Schied et al. 2017 (for consecutive frames)");
    return kExitOk;
}

}  // namespace fovea::app
