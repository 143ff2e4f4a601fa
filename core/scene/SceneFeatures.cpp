#include "core/scene/SceneFeatures.h"

namespace fovea::scene {

std::vector<std::string> sceneFeatureNames(uint32_t mask) {
    static const char* kNames[] = {"geometry",        "emissive", "textures",
                                   "punctual-lights", "stereo",   "environment"};
    std::vector<std::string> out;
    for (uint32_t i = 0; i < 6; ++i)
        if (mask & (1u << i)) out.push_back(kNames[i]);
    return out;
}

}  // namespace fovea::scene
