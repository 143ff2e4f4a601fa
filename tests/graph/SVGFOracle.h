// Double-precision CPU twin of the SVGF pass (shaders/svgf/*.comp; Schied et al. 2017 §4.1-4.4)
// for a static scene seen through a still camera (zero motion: every pixel reprojects onto
// itself). Used by tests/graph/SVGFOracleTests.cpp: closed forms on the CPU, and GPU = oracle.
#pragma once
#include <vector>

namespace fovea::testsvgf {

struct SVGFOracleParams {
    int iterations = 5;
    int feedbackTap = 1;  // 1-based level; 0 = the unfiltered accumulation
    double alpha = 0.2, momentsAlpha = 0.2;
    double sigmaLuminance = 4.0, sigmaNormal = 128.0, sigmaDepth = 1.0;
    double historyForVariance = 4.0;
    int spatialRadius = 3;
    double maxHistory = 32.0;
};

// One frame's G-buffer (RGBA per pixel; depth in x) and colour, as the pass reads them.
struct SVGFOracleFrame {
    int width = 0, height = 0;
    const std::vector<float>* color = nullptr;
    const std::vector<float>* normal = nullptr;
    const std::vector<float>* depth = nullptr;
    const std::vector<float>* albedo = nullptr;    // may be null: 1
    const std::vector<float>* emission = nullptr;  // may be null: 0
};

double luminance709(const double* c);

class SVGFOracle {
public:
    explicit SVGFOracle(SVGFOracleParams p) : mP(p) {}
    // Runs one frame; history restarts when `history` is false (first frame, cut).
    void frame(const SVGFOracleFrame& f, bool history = true);
    // Outputs of the last frame, RGBA per pixel (as the pass's outputs).
    const std::vector<double>& accumulated() const { return mAccumulated; }
    const std::vector<double>& illumination() const { return mIllumination; }
    const std::vector<double>& filtered() const { return mFiltered; }

    // One a-trous level (§4.3) on `in` (rgb colour, a = variance) at step 2^level; `hasData` is
    // 1 where a pixel holds data (h > 0). Public for the closed-form tests.
    static std::vector<double> atrousLevel(const SVGFOracleParams& p, int w, int h,
                                           const std::vector<double>& in,
                                           const std::vector<float>& normal,
                                           const std::vector<float>& depth,
                                           const std::vector<char>& hasData, int level);

private:
    SVGFOracleParams mP;
    std::vector<double> mHistColor, mHistMoments, mHistLength;  // rgb+a / 2 / 1 per pixel
    std::vector<double> mAccumulated, mIllumination, mFiltered;
};

}  // namespace fovea::testsvgf
