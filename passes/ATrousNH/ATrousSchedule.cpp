#include "passes/ATrousNH/ATrousSchedule.h"

#include <algorithm>

namespace fovea::passes {

std::vector<ATrousDispatch> buildATrousSchedule(const ATrousScheduleOptions& o) {
    std::vector<ATrousDispatch> out;
    const int layers = std::clamp(o.layerCount, 1, 3);
    int iters[3];
    int most = 0;
    for (int l = 0; l < 3; ++l) {
        iters[l] = l < layers ? std::clamp(o.iterations[l], 0, 16) : 0;
        most = std::max(most, iters[l]);
    }
    if (o.perLayer) {
        // Algorithm 1: for each layer, its own levels i = n-1 .. 0 (or 0 .. n-1).
        for (int l = 0; l < layers; ++l)
            for (int j = 0; j < iters[l]; ++j) {
                int level = o.decreasing ? iters[l] - 1 - j : j;
                out.push_back({1u << l, 1 << level, false});
            }
    } else {
        // One dispatch per level for all layers at once (max(M, N, P) dispatches instead of
        // M + N + P). Each layer still sees exactly Algorithm 1's step sequence: with decreasing
        // steps the layers are aligned at their last (step 1) iteration, with increasing steps at
        // their first.
        for (int k = 0; k < most; ++k) {
            ATrousDispatch d;
            int level = o.decreasing ? most - 1 - k : k;
            d.step = 1 << level;
            for (int l = 0; l < layers; ++l) {
                bool active = o.decreasing ? k >= most - iters[l] : k < iters[l];
                if (active) d.layers |= 1u << l;
            }
            out.push_back(d);
        }
    }
    if (o.fill) {
        // Levels 1, 2, 4, ... : after level k a single valid pixel has filled the square of
        // radius 2 (2^(k+1) - 1) around it without gaps (each square is wider than the next step),
        // so stopping once that radius reaches fillReach fills every pixel of an eye that holds
        // at least one value.
        const uint32_t all = (1u << layers) - 1u;
        for (int k = 0; k < 24; ++k) {
            out.push_back({all, 1 << k, true});
            if (2 * ((2 << k) - 1) >= o.fillReach) break;
        }
    }
    if (out.empty()) out.push_back({0u, 1, false});
    return out;
}

}  // namespace fovea::passes
