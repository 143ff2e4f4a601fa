// Step 4 of loading a glTF file: tinygltf parses the checked document and loads its buffers.
// tinygltf sees a pruned copy of the JSON: every entity the scene does not use is replaced by a
// minimal valid stub (indices stay stable), animations and skins are dropped, and images are
// emptied (fovea reads and decodes image bytes itself). This keeps tinygltf away from the broken
// parts that are only worth a warning, and from its unchecked paths — it reads an image's buffer
// view without a bounds check and throws std::out_of_range on a GLB buffer of byteLength 0.
#pragma once
#include "core/scene/gltf/GltfDocument.h"
#include "core/scene/gltf/GltfUsage.h"
#include "core/scene/gltf/TinyGltf.h"

namespace fovea::scene::gltf {

// Throws InputError(file, "", "tinygltf: ...") if tinygltf fails, and InputError naming the
// buffer if a used buffer's loaded size differs from its byteLength.
tinygltf::Model loadTinyGltf(const GltfDocument& doc, const GltfUsage& usage);

}  // namespace fovea::scene::gltf
