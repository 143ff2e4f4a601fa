// Helpers shared by the scene loading tests (SceneLoadTests.cpp, GltfSyntheticTests.cpp).
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include "core/scene/gltf/GltfLoader.h"
#include "core/scene/SceneLoader.h"
#include "core/util/Error.h"

namespace fovea::scenetest {

namespace fs = std::filesystem;
using namespace fovea::scene;

inline fs::path scenesDir() {
    return fs::path(FOVEA_SOURCE_DIR) / ".." / "shared" / "scenes";
}

#define REQUIRE_SCENES()                                                             \
    do {                                                                             \
        if (!fs::exists(scenesDir())) GTEST_SKIP() << scenesDir() << " not present"; \
    } while (0)

inline Scene load(const std::string& relative) {
    Scene scene = loadScene((scenesDir() / relative).string());
    if (std::getenv("FOVEA_SCENE_VERBOSE")) {
        for (const std::string& w : scene.warnings)
            std::cout << relative << ": warning: " << w << "\n";
    }
    return scene;
}

// The InputError a load throws ("" pointer/message if it loads).
inline InputError loadError(const fs::path& file, bool drawEveryMesh = false) {
    try {
        GltfLoadOptions options;
        options.drawEveryMesh = drawEveryMesh;
        loadGltf(file, options);
    } catch (const InputError& e) {
        return e;
    }
    ADD_FAILURE() << file << " loaded, an InputError was expected";
    return InputError("", "", "");
}

inline bool anyWarningContains(const Scene& scene, const std::string& text) {
    return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                       [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

inline float maxEmission(const Scene& scene) {
    float best = 0.0f;
    for (const Material& m : scene.materials)
        best = std::max({best, m.emissive.r, m.emissive.g, m.emissive.b});
    return best;
}

inline size_t emissiveTriangles(const Scene& scene) {
    size_t n = 0;
    for (uint32_t id : scene.mesh.materialIds) n += scene.materials.at(id).isEmissive();
    return n;
}

// Every loaded scene must be internally consistent, whatever the file was.
inline void expectConsistent(const Scene& s) {
    const TriangleMesh& m = s.mesh;
    ASSERT_EQ(m.normals.size(), m.positions.size());
    ASSERT_EQ(m.uvs.size(), m.positions.size());
    ASSERT_EQ(m.materialIds.size(), m.triangles.size());
    ASSERT_FALSE(s.materials.empty());
    for (const glm::uvec3& t : m.triangles) {
        ASSERT_LT(std::max({t.x, t.y, t.z}), m.positions.size());
    }
    for (uint32_t id : m.materialIds) ASSERT_LT(id, s.materials.size());
    for (size_t i = 0; i < m.positions.size(); ++i) {
        ASSERT_TRUE(std::isfinite(m.positions[i].x + m.positions[i].y + m.positions[i].z));
        ASSERT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-3f);
    }
    for (const Texture& t : s.textures) ASSERT_EQ(t.rgba8.size(), size_t(t.width) * t.height * 4);
    ASSERT_FALSE(s.bounds.empty());
}

}  // namespace fovea::scenetest
