// Step 3 of loading a glTF file: the checks tinygltf does not do, run on the raw JSON of every
// entity (used or not) before tinygltf sees it. Each problem is recorded as an Issue with its JSON
// pointer; the loader turns the ones in used entities into an InputError and the others into
// warnings. Checked: types of every property fovea reads, references in range, buffer / buffer
// view / accessor bounds (with overflow-safe arithmetic), alignment and strides, attribute and
// index formats, sparse accessors, node transforms, material factors, image sources, cameras,
// lights, the asset version and required extensions.
// Data checks that need the bytes (index values, finite positions, sparse index order, image
// decoding) happen while reading, in GltfAccessor / GltfMesh / GltfTextures.
#pragma once
#include <string>
#include <vector>

#include "core/scene/gltf/GltfDocument.h"
#include "core/scene/gltf/GltfJson.h"

namespace fovea::scene::gltf {

// Extensions fovea implements; a file that requires any other one is rejected.
const std::vector<std::string>& supportedExtensions();

// Root, asset, extension lists, references, nodes, meshes, materials, textures, images, cameras,
// lights (GltfValidate.cpp). Unsupported optional extensions go straight to `warnings`.
void validateStructure(const GltfJson& gltf, const GltfDocument& doc,
                       std::vector<std::string>& warnings);

// Buffers, buffer views, accessors and the formats of the attributes fovea reads
// (GltfValidateData.cpp).
void validateData(const GltfJson& gltf, const GltfDocument& doc);

// A URI that is neither a data URI nor a relative path (http:, file:, ...): fovea only loads files
// next to the glTF file.
bool hasUriScheme(const std::string& uri);

// The decoded size of a base64 payload, or false if it is not valid base64.
bool base64DecodedSize(const std::string& payload, uint64_t& size);

}  // namespace fovea::scene::gltf
