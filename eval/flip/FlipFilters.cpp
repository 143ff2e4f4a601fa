#include "eval/flip/FlipFilters.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <thread>

namespace fovea::eval::flip {

namespace {

// Runs body(firstRow, endRow) over [0, rows) in contiguous chunks on the machine's cores: the
// filters are most of ꟻLIP's cost, and rows are independent.
template <class Body>
void parallelRows(uint32_t rows, Body body) {
    const uint32_t threads =
        std::clamp<uint32_t>(std::thread::hardware_concurrency(), 1u, std::max(rows / 16u, 1u));
    if (threads <= 1) {
        body(0u, rows);
        return;
    }
    std::vector<std::jthread> pool;
    const uint32_t chunk = (rows + threads - 1) / threads;
    for (uint32_t first = 0; first < rows; first += chunk)
        pool.emplace_back([=] { body(first, std::min(rows, first + chunk)); });
}

Kernel normalized(Kernel k) {
    double sum = 0;
    for (float v : k) sum += v;
    // Every kernel here is a sampled Gaussian with its centre weight exp(0) = 1: sum >= 1.
    for (float& v : k) v = float(v / sum);
    return k;
}

// Positive weights scaled to sum 1, negative ones to -1 (FLIP's feature kernels).
Kernel signNormalized(Kernel k) {
    double positive = 0, negative = 0;
    for (float v : k) (v > 0 ? positive : negative) += v;
    for (float& v : k) {
        // Both derivative kernels have weights of each sign for any radius >= 1 (featureKernels
        // keeps the radius >= 1); the guards only keep a degenerate kernel finite.
        if (v > 0 && positive > 0) v = float(v / positive);
        if (v < 0 && negative < 0) v = float(v / -negative);
    }
    return k;
}

}  // namespace

Plane convolveSeparable(const Plane& in, const Kernel& rows, const Kernel& columns) {
    const int w = int(in.width), h = int(in.height);
    Plane mid(in.width, in.height), out(in.width, in.height);
    const int rr = int(rows.size() / 2), rc = int(columns.size() / 2);
    // Rows: the clamp only near the left and right edges; the same sum order everywhere.
    parallelRows(in.height, [&](uint32_t y0, uint32_t y1) {
        for (int y = int(y0); y < int(y1); ++y) {
            const float* src = &in.values[size_t(y) * size_t(w)];
            float* dst = &mid.values[size_t(y) * size_t(w)];
            for (int x = 0; x < w; ++x) {
                float sum = 0;
                if (x >= rr && x + rr < w) {
                    for (int k = -rr; k <= rr; ++k) sum += rows[size_t(k + rr)] * src[x + k];
                } else {
                    for (int k = -rr; k <= rr; ++k)
                        sum += rows[size_t(k + rr)] * src[std::clamp(x + k, 0, w - 1)];
                }
                dst[x] = sum;
            }
        }
    });
    // Columns: whole rows scaled and added (contiguous, so the compiler vectorizes it), tap by
    // tap in the same order as the rows.
    parallelRows(in.height, [&](uint32_t y0, uint32_t y1) {
        for (int y = int(y0); y < int(y1); ++y) {
            float* dst = &out.values[size_t(y) * size_t(w)];
            for (int k = -rc; k <= rc; ++k) {
                const float* src = &mid.values[size_t(std::clamp(y + k, 0, h - 1)) * size_t(w)];
                const float weight = columns[size_t(k + rc)];
                for (int x = 0; x < w; ++x) dst[x] += weight * src[x];
            }
        }
    });
    return out;
}

int csfRadius(double pixelsPerDegree) {
    constexpr double kWidestB = 0.04;  // b1 of the blue-yellow CSF, the widest Gaussian
    const double pi = std::numbers::pi;
    return int(std::ceil(3.0 * std::sqrt(kWidestB / (2.0 * pi * pi)) * pixelsPerDegree));
}

std::vector<CsfTerm> csfTerms(CsfChannel channel, double pixelsPerDegree) {
    struct Gaussians {
        double a1, b1, a2, b2;
    };
    // FLIP's fits of the CSFs of Mullen (1985) / Johnson and Fairchild (2003).
    const Gaussians g = channel == CsfChannel::Achromatic ? Gaussians{1.0, 0.0047, 0.0, 1e-5}
                        : channel == CsfChannel::RedGreen ? Gaussians{1.0, 0.0053, 0.0, 1e-5}
                                                          : Gaussians{34.1, 0.04, 13.5, 0.025};
    const int r = csfRadius(pixelsPerDegree);
    const double pi = std::numbers::pi;
    std::vector<CsfTerm> terms;
    double total = 0;
    for (auto [a, b] : {std::pair{g.a1, g.b1}, std::pair{g.a2, g.b2}}) {
        if (a == 0) continue;
        Kernel k(size_t(2 * r + 1));
        double sum = 0;
        for (int i = -r; i <= r; ++i) {
            const double x = i / pixelsPerDegree;  // degrees
            k[size_t(i + r)] = float(std::exp(-pi * pi * x * x / b));
            sum += k[size_t(i + r)];
        }
        // The term's share of the 2D kernel's sum: a √(π/b) (Σ_i k_i)².
        const double weight = a * std::sqrt(pi / b) * sum * sum;
        terms.push_back({float(weight), normalized(std::move(k))});
        total += weight;
    }
    for (auto& t : terms) t.weight = float(t.weight / total);  // total > 0: a1 > 0 for every CSF
    return terms;
}

FeatureKernels featureKernels(double pixelsPerDegree) {
    constexpr double kFeatureWidthDegrees = 0.082;
    FeatureKernels f;
    f.sigma = float(0.5 * kFeatureWidthDegrees * pixelsPerDegree);
    // At least one pixel each side, so that both derivative kernels have weights of both signs.
    f.radius = std::max(1, int(std::ceil(3.0 * f.sigma)));
    const size_t n = size_t(2 * f.radius + 1);
    f.smooth.resize(n);
    f.edge.resize(n);
    f.point.resize(n);
    const double s2 = double(f.sigma) * f.sigma;  // sigma > 0: ppd is checked positive
    for (int i = -f.radius; i <= f.radius; ++i) {
        const double g = std::exp(-double(i) * i / (2.0 * s2));
        f.smooth[size_t(i + f.radius)] = float(g);
        f.edge[size_t(i + f.radius)] = float(-i * g);
        f.point[size_t(i + f.radius)] = float((double(i) * i / s2 - 1.0) * g);
    }
    f.smooth = normalized(std::move(f.smooth));
    f.edge = signNormalized(std::move(f.edge));
    f.point = signNormalized(std::move(f.point));
    return f;
}

}  // namespace fovea::eval::flip
