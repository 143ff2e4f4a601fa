#include "core/scene/SceneFeatures.h"

#include <iterator>

namespace fovea::scene {

std::vector<std::string> sceneFeatureNames(uint32_t mask) {
    static const char* kNames[] = {"geometry", "emissive",    "textures", "punctual-lights",
                                   "stereo",   "environment", "alpha",    "equirect"};
    std::vector<std::string> out;
    for (uint32_t i = 0; i < std::size(kNames); ++i)
        if (mask & (1u << i)) out.push_back(kNames[i]);
    return out;
}

}  // namespace fovea::scene
