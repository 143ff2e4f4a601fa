// Scalar CPU reference of the ATrousNH pass (shaders/atrous_nh/atrous_nh.comp): the same
// schedule, weights, mask rule and hole filling, in plain loops, for the GPU-vs-CPU tests.
#pragma once
#include <cstdint>
#include <vector>

#include "passes/ATrousNH/ATrousSchedule.h"

namespace fovea::testref {

struct ATrousRefInput {
    int width = 0, height = 0;
    int eyes = 1;
    int layerCount = 1;
    std::vector<float> color;     // rgba per pixel
    std::vector<float> normal;    // rgba per pixel; empty = no normal weight
    std::vector<float> position;  // rgba per pixel; empty = no position weight
    std::vector<uint32_t> mask;   // FoveationMask words; empty = no mask
    float sigmaColor = 1.0f, sigmaNormal = 0.2f, sigmaPosition = 0.5f;  // 0 = term off
    // positionTerm: true = plane |n_p . (x_q - x_p)| (needs `normal`; a hit/miss pair, position.w
    // differing, has weight 0) times the sigmaTangent weight on the distance along the plane
    // (0 = off), false = distance |x_q - x_p|. Scene units (positionUnit scene).
    bool positionPlane = true;
    float sigmaTangent = 0.0f;
    std::vector<passes::ATrousDispatch> schedule;
};

// Returns rgba per pixel: the denoised colour, a = 1 with a value, 0 without.
std::vector<float> atrousReference(const ATrousRefInput& in);

}  // namespace fovea::testref
