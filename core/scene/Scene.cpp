#include "core/scene/Scene.h"

#include <algorithm>
#include <cmath>

#include "core/scene/Environment.h"
#include "core/scene/SceneFeatures.h"

namespace fovea::scene {

namespace {

constexpr float kDefaultYfov = 0.7853982f;  // 45 degrees, docs/scenes.md "Default camera"

}  // namespace

uint32_t Scene::features() const {
    uint32_t bits = 0;
    if (!mesh.triangles.empty()) bits |= kSceneGeometry;
    // Only materials some triangle uses count: an emissive or textured material nothing draws
    // gives a pass nothing to work on.
    std::vector<char> used(materials.size(), 0);
    for (uint32_t id : mesh.materialIds) {
        if (id < used.size()) used[id] = 1;
    }
    for (size_t i = 0; i < materials.size(); ++i) {
        if (!used[i]) continue;
        const Material& m = materials[i];
        if (m.isEmissive()) bits |= kSceneEmissive;
        if (m.hasAlphaTest()) bits |= kSceneAlpha;
        if (m.baseColorTexture >= 0 || m.emissiveTexture >= 0 || m.metallicRoughnessTexture >= 0 ||
            m.normalTexture >= 0) {
            bits |= kSceneTextures;
        }
    }
    if (!lights.empty()) bits |= kScenePunctual;
    if (environment) {
        bool emits = false;
        for (const glm::vec3& c : environment->radiance)
            if (c != glm::vec3(0.0f)) {
                emits = true;
                break;
            }
        if (emits) bits |= kSceneEnvironment;
    }
    return bits;
}

CameraDesc Scene::defaultCamera() const {
    CameraDesc camera;
    camera.name = "default";
    camera.yfov = kDefaultYfov;
    if (bounds.empty()) return camera;
    glm::vec3 center = bounds.center();
    float radius = 0.5f * glm::length(bounds.extent());
    // A point-sized scene still needs a distance to look from; 1 unit keeps the numbers sane.
    if (!(radius > 0.0f) || !std::isfinite(radius)) radius = 1.0f;
    // The sphere of radius r seen from distance d fills the vertical FOV when r / d = sin(fov/2).
    float distance = radius / std::sin(0.5f * camera.yfov);
    // Look the way the scene's own first camera looks, if it has one: a room (the Cornell box)
    // is authored to be seen from its open side, and a view from another side sees a closed wall.
    // Without a camera: from +z towards -z (glTF's default camera orientation).
    glm::vec3 direction(0.0f, 0.0f, -1.0f), up(0.0f, 1.0f, 0.0f);
    if (!cameras.empty()) {
        const glm::vec3 d = cameras.front().target - cameras.front().position;
        const float length = glm::length(d);
        // A degenerate camera (target on the eye, non-finite) keeps the default direction.
        if (length > 0.0f && std::isfinite(length)) {
            direction = d / length;
            const glm::vec3 u = cameras.front().up;
            if (glm::length(glm::cross(u, direction)) > 1e-3f)
                up = glm::normalize(u);
            else
                up = std::abs(direction.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, -1);
        }
    }
    camera.position = center - direction * distance;
    camera.target = center;
    camera.up = up;
    // The near plane scales with the scene (mm and m files alike) and stays in front of it.
    camera.znear = std::max(1e-3f * radius, 1e-6f);
    return camera;
}

}  // namespace fovea::scene
