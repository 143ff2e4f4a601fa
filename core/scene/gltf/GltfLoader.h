// glTF 2.0 (.gltf / .glb) to fovea's flattened Scene. The supported subset, the checks and what
// is a warning rather than an error are listed in docs/scenes.md.
//
// The pipeline (one file per step): GltfDocument (bytes, GLB container, JSON) -> GltfValidate
// (every entity, problems recorded with their JSON pointer) -> GltfUsage (what the chosen scene
// uses: problems there are errors, elsewhere warnings) -> GltfTiny (tinygltf loads the pruned
// document) -> GltfMesh / GltfMaterials / GltfTextures (world-space triangles, materials, texels).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "core/scene/Scene.h"

namespace fovea::scene {

struct GltfLoadOptions {
    // Also draw, once and untransformed, every mesh that no node of the scene draws. For test
    // suites whose files hold meshes without a node hierarchy (the Khronos validator's): their
    // data is then used, and therefore checked. Off for rendering: glTF draws only what the
    // scene's nodes reference.
    bool drawEveryMesh = false;
    // Read buffer/image files outside the scene file's folder (absolute paths, "../"). Off by
    // default: a downloaded scene must not make fovea open /etc/shadow (`--allow-external-uris`).
    bool allowExternalUris = false;
};

// What a load used, for tests that compare fovea's verdict with an external validator's report.
struct GltfLoadReport {
    // Entity-level JSON pointers the scene is built from: "/nodes/0", "/meshes/1/primitives/0",
    // "/accessors/3", ... Filled once the scene graph has been walked, even if the load then fails.
    std::vector<std::string> usedPointers;
};

// Throws InputError(file, pointer, message) for anything wrong in what the scene uses and when
// there is nothing to draw (no triangles); never crashes or hangs on any input.
Scene loadGltf(const std::filesystem::path& path, const GltfLoadOptions& options = {},
               GltfLoadReport* report = nullptr);

}  // namespace fovea::scene
