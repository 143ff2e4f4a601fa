// CPU oracle for BMFR's per-block fit (seed 003, P2 Eq. 2/3): the least-squares projection of
// the noisy target onto the span of the block's features, in double precision with Eigen.
// Positions are centred on the block mean before squaring (only the span matters: it equals the
// span of the GPU's min/max-scaled features). A rank-deficient block gets the minimum-norm
// solution (complete orthogonal decomposition), whose prediction is still the unique projection.
#pragma once
#include <vector>

namespace fovea::testref {

struct BMFRBlockInput {
    // One entry per valid pixel of the block.
    std::vector<double> position;  // xyz per pixel
    std::vector<double> normal;    // xyz per pixel
    std::vector<double> albedo;    // rgb per pixel; empty = not a feature
    std::vector<double> target;    // rgb per pixel (z)
};

struct BMFRBlockFit {
    std::vector<double> fitted;       // rgb per pixel
    double residual2[3] = {0, 0, 0};  // sum of squared residuals per channel
    int rank = 0;
};

// Features [1, n.xyz, w.xyz, w.xyz^2] (+ albedo.rgb) and their least-squares fit.
BMFRBlockFit bmfrOracleFit(const BMFRBlockInput& in);

}  // namespace fovea::testref
