// Step 1 of loading a glTF file: the bytes. Reads .gltf or .glb (recognised by content: a GLB
// starts with the magic "glTF"), splits and checks the GLB container strictly — tinygltf 2.7.0
// checks the BIN chunk length against the GLB length with an off-by-8 error and rejects unknown
// chunks — and parses the JSON with fovea's parser (exact line/column errors, duplicate keys
// rejected). Everything here is fatal: without a sound container and JSON there is no scene.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/gltf/GltfJson.h"
#include "core/util/UserFile.h"

namespace fovea::scene::gltf {

struct GltfDocument {
    std::string file;               // the path as given, for messages
    std::filesystem::path baseDir;  // where relative URIs are resolved
    Json json;
    bool isGlb = false;
    std::optional<std::vector<uint8_t>> glbBin;  // the GLB's BIN chunk, if it has one
    std::vector<std::string> warnings;           // e.g. bytes after the end of a GLB
    // Buffer and image URIs may name files outside the scene's folder (GltfLoadOptions).
    bool allowExternalUris = false;
};

// True when a percent-decoded relative URI names a file outside the folder it is resolved in:
// an absolute path, a root name, or ".." climbing above it ("../../../../etc/shadow").
bool uriLeavesFolder(const std::string& decoded);
// The message for such a URI: names the URI as written (shortened), but no size or content of
// the file is echoed: it is never opened.
std::string externalUriMessage(const std::string& uri);

// Throws InputError(file, "", ...) for unreadable files, broken GLB containers and bad JSON.
GltfDocument readGltfDocument(const std::filesystem::path& path);

// Files are read with readRegularFile (core/util/UserFile.h): no FIFOs or devices.

// Size limits: tinygltf addresses a GLB with 32-bit lengths; images are decoded to RGBA8 in memory.
constexpr uint64_t kMaxGltfFileBytes = uint64_t(2) << 30;
constexpr uint64_t kMaxImageFileBytes = uint64_t(256) << 20;

}  // namespace fovea::scene::gltf
