// CPU oracle for BMFR's published variant (docs/passes/BMFR.md#variants): the per-block fit as the
// authors' OpenCL code computes it (maZZZu/bmfr opencl/bmfr.cl `fitter` and `weighted_sum`,
// seed 003 P2 §3.3-3.4), in double precision with Eigen. Unlike BMFROracle (a pure projection,
// independent of scaling), this one reproduces what the published choices change: the raw
// features and their [0, 1] scaling, the regularization noise (the same hash, so the noisy
// system is the GPU's), the rows a block holds (mirrored edges, misses) and the clamp at 0.
#pragma once
#include <cstdint>
#include <vector>

namespace fovea::testref {

inline constexpr int kPublishedBlockPixels = 1024;  // 32x32, row = y * 32 + x

// bmfr.cl add_random: noise in [-epsilon, epsilon) for (row in block, feature column, frame);
// float arithmetic as the kernel does it. `columns` = features + 3 colour channels (13).
float bmfrPublishedNoise(uint32_t row, uint32_t column, uint32_t frame, float epsilon,
                         uint32_t columns = 13);

struct BMFRPublishedBlock {
    // kPublishedBlockPixels rows in block order; a row with used[r] = false is not in the fit.
    std::vector<bool> used;
    std::vector<double> position, normal, target;  // xyz / rgb per row
};

// The fit of one block, evaluated on the noise-free scaled features of every used row and clamped
// at 0 (rgb per row; unused rows 0).
std::vector<double> bmfrPublishedFit(const BMFRPublishedBlock& block, uint32_t frame,
                                     float epsilon);

}  // namespace fovea::testref
