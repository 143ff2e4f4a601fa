// What a loaded scene provides, as bits. Passes declare the bits they need (Pass::sceneNeeds) and
// the graph compiler culls a pass whose needs the scene does not meet; the scene computes its own
// bits (Scene::features, SceneGpu::features). The bits belong to the scene, so core/scene does not
// depend on core/graph.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace fovea::scene {

enum SceneFeature : uint32_t {
    kSceneGeometry = 1u << 0,     // any triangles at all (a scene was loaded)
    kSceneEmissive = 1u << 1,     // emissive triangles
    kSceneTextures = 1u << 2,     // textured materials
    kScenePunctual = 1u << 3,     // point/spot/directional lights
    kSceneStereo = 1u << 4,       // a stereo camera rig
    kSceneEnvironment = 1u << 5,  // an environment map that emits (--env)
    kSceneAlpha = 1u << 6,        // materials with alphaMode MASK (cutoff > 0) or BLEND
    kSceneEquirect = 1u << 7,     // a 360° equirect camera (CameraModel::Equirect)
};

// "geometry", "emissive", "textures", "punctual-lights", "stereo", "environment",
// "alpha", "equirect" for the set bits.
std::vector<std::string> sceneFeatureNames(uint32_t mask);

}  // namespace fovea::scene
