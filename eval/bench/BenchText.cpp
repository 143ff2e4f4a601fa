// Table text shared by bench.csv/bench.md (BenchOutputs.cpp) and the seed tables (BenchSeeds.cpp,
// which the unit tests also compile).
#include <cmath>
#include <cstdio>

#include "eval/bench/Bench.h"

namespace fovea::eval {

std::string benchNumber(double v, const char* format) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return "inf";  // PSNR of identical images
    char text[64];
    std::snprintf(text, sizeof text, format, v);
    return text;
}

std::string benchMarkdown(const std::string& s) {
    std::string out;
    for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}

}  // namespace fovea::eval
