// The one entry point for "which scene": "builtin:<name>" selects a built-in scene
// (BuiltinScenes.h), anything else is a glTF file path (.gltf or .glb).
#pragma once
#include <string>

#include "core/scene/Scene.h"

namespace fovea::scene {

// Throws InputError naming the spec/file for unknown built-ins, unsupported extensions,
// unreadable files and every glTF problem (see GltfLoader.h).
// `allowExternalUris`: see GltfLoadOptions.
Scene loadScene(const std::string& spec, bool allowExternalUris = false);

}  // namespace fovea::scene
