// The dispatch schedule of the non-homogeneous à-trous denoiser (seed 000 §3.4, Algorithm 1):
// which layers each dispatch updates and with which step width. Pure CPU, no Vulkan, so the test
// reference and the pass share one definition of "which iteration runs when".
#pragma once
#include <cstdint>
#include <vector>

namespace fovea::passes {

struct ATrousDispatch {
    uint32_t layers = 0;  // bit l set: pixels of layer l are updated (others are copied through)
    int step = 1;         // tap spacing in pixels (2^i)
    bool fill = false;    // hole-fill level: only pixels without a value are updated
};

struct ATrousScheduleOptions {
    int layerCount = 1;             // 1..3
    int iterations[3] = {5, 0, 0};  // per layer (seed 000: M, N, P)
    bool decreasing = true;         // Qi et al. / seed 000 Fig. 7: 2^(n-1) .. 1; else 1 .. 2^(n-1)
    bool perLayer = false;  // true: Algorithm 1 literally (layer after layer); false: by level
    bool fill = true;       // append hole-fill levels covering `fillReach` pixels
    int fillReach = 1;      // largest distance a fill must bridge (max(eye width, height))
};

// Never empty: with nothing to do it is one copy dispatch (layers = 0).
std::vector<ATrousDispatch> buildATrousSchedule(const ATrousScheduleOptions& o);

}  // namespace fovea::passes
