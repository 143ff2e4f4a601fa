#include "tests/graph/BMFRPublishedOracle.h"

#include <Eigen/Dense>
#include <algorithm>

namespace fovea::testref {

float bmfrPublishedNoise(uint32_t row, uint32_t column, uint32_t frame, float epsilon,
                         uint32_t columns) {
    uint32_t a = row + column * kPublishedBlockPixels + frame * columns * kPublishedBlockPixels;
    // The integer hash bmfr.cl's `random` credits to asgerhoedt.dk/?p=323.
    a = (a + 0x7ed55d16u) + (a << 12);
    a = (a ^ 0xc761c23cu) ^ (a >> 19);
    a = (a + 0x165667b1u) + (a << 5);
    a = (a + 0xd3a2646cu) ^ (a << 9);
    a = (a + 0xfd7046c5u) + (a << 3);
    a = (a ^ 0xb55a4f09u) ^ (a >> 16);
    return epsilon * 2.0f * (float(a) / 4294967296.0f - 0.5f);
}

std::vector<double> bmfrPublishedFit(const BMFRPublishedBlock& block, uint32_t frame,
                                     float epsilon) {
    constexpr int kFeatures = 10;
    std::vector<int> rows;
    for (int r = 0; r < kPublishedBlockPixels; ++r)
        if (block.used[size_t(r)]) rows.push_back(r);
    std::vector<double> out(size_t(kPublishedBlockPixels) * 3, 0.0);
    if (rows.empty()) return out;

    // Raw features [1, n, w, w^2] (P2 Eq. 8, bmfr.cpp FEATURE_BUFFERS).
    const Eigen::Index n = Eigen::Index(rows.size());
    Eigen::MatrixXd t(n, kFeatures), z(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
        const size_t k = size_t(rows[size_t(i)]) * 3;
        t(i, 0) = 1.0;
        for (int c = 0; c < 3; ++c) {
            const double w = block.position[k + c];
            t(i, 1 + c) = block.normal[k + c];
            t(i, 4 + c) = w;
            t(i, 7 + c) = w * w;
            z(i, c) = block.target[k + c];
        }
    }
    // bmfr.cl `scale` on the position columns: to [0, 1] when the block range exceeds 1, else
    // only shifted to start at 0.
    for (int m = 4; m < kFeatures; ++m) {
        const double lo = t.col(m).minCoeff(), hi = t.col(m).maxCoeff();
        const double inv = hi - lo > 1.0 ? 1.0 / (hi - lo) : 1.0;
        t.col(m) = ((t.col(m).array() - lo) * inv).matrix();
    }
    // Noise on every column but the constant one, for the fit only.
    Eigen::MatrixXd noisy = t;
    for (Eigen::Index i = 0; i < n; ++i)
        for (int m = 1; m < kFeatures; ++m)
            noisy(i, m) +=
                double(bmfrPublishedNoise(uint32_t(rows[size_t(i)]), uint32_t(m), frame, epsilon));
    const Eigen::MatrixXd alpha = noisy.colPivHouseholderQr().solve(z);
    const Eigen::MatrixXd y = t * alpha;
    for (Eigen::Index i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
            out[size_t(rows[size_t(i)]) * 3 + size_t(c)] = std::max(0.0, y(i, c));
    return out;
}

}  // namespace fovea::testref
