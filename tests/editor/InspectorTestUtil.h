// Helpers of the `fovea inspect` tests under Xvfb (InspectorTests.cpp, InspectorFeatureTests.cpp):
// running the inspector through a shell prefix and reading its screenshots with their JSON.
#pragma once
#include <gtest/gtest.h>

#include "tests/cli/CliTestUtil.h"

namespace fovea::clitest {

inline const fs::path kStatuses = kRepo / "graphs" / "tests" / "inspector_statuses.json";

// Runs `prefix fovea args...` through the shell (prefix: xvfb-run or env settings).
inline Result shellRun(const std::string& prefix, const std::vector<std::string>& args) {
    TempDir capture;
    Result r;
    r.command = prefix + " " + shellQuote(FOVEA_EXE);
    for (const auto& a : args) r.command += " " + shellQuote(a);
    const std::string line = r.command + " </dev/null >" +
                             shellQuote((capture / "stdout").string()) + " 2>" +
                             shellQuote((capture / "stderr").string());
    const int status = std::system(line.c_str());
    r.code = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : 1000;
    r.out = readText(capture / "stdout");
    r.err = readText(capture / "stderr");
    return r;
}

// CI installs xvfb (scripts/install-deps.sh): a missing xvfb-run is a broken setup, not a skip.
inline std::string xvfbPrefix() {
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) return "";
    return "xvfb-run -a -s '-screen 0 1024x768x24'";
}

struct Shot {
    image::ImageRGBA pixels;
    json info;
};

inline Shot readShot(const fs::path& png) {
    Shot s{image::readImage(png), json::parse(readText(png.string() + ".json"))};
    return s;
}

// Mean and standard deviation of the luminance of the previewed image's rectangle.
inline std::pair<double, double> previewStats(const Shot& s) {
    const auto r = s.info["preview"]["image"];
    const int x0 = r[0], y0 = r[1], w = r[2], h = r[3];
    double sum = 0, sum2 = 0;
    size_t n = 0;
    for (int y = y0; y < y0 + h; ++y)
        for (int x = x0; x < x0 + w; ++x) {
            const float* p = &s.pixels.pixels[(size_t(y) * s.pixels.width + size_t(x)) * 4];
            const double l = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            sum += l;
            sum2 += l * l;
            ++n;
        }
    if (n == 0) return {0.0, 0.0};
    const double mean = sum / double(n);
    return {mean, std::sqrt(std::max(0.0, sum2 / double(n) - mean * mean))};
}

}  // namespace fovea::clitest
