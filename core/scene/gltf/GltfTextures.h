// glTF images to RGBA8 texels. fovea finds the encoded bytes itself (data URI, file next to the
// glTF file, or buffer view) and decodes them with stb_image (libstb-dev): 1 to 4 channels are
// expanded to RGBA, 16-bit images are rounded to 8 bits. Only images the scene uses are decoded;
// the others are probed (header only) so that a broken one is reported as a warning.
#pragma once
#include <string>
#include <vector>

#include "core/scene/gltf/GltfDocument.h"
#include "core/scene/gltf/GltfUsage.h"
#include "core/scene/Scene.h"
#include "core/scene/gltf/TinyGltf.h"

namespace fovea::scene::gltf {

// Throws InputError(file, "/images/<index>", reason) if the image cannot be read or decoded.
Texture decodeImage(const GltfDocument& doc, const tinygltf::Model& model, size_t index);

// One warning per unused image that is unreadable or not a decodable PNG/JPEG.
void probeUnusedImages(const GltfDocument& doc, const GltfUsage& usage,
                       std::vector<std::string>& warnings);

// Standard base64 (RFC 4648) to bytes; false on a malformed payload.
bool base64Decode(const std::string& text, std::vector<uint8_t>& out);

// Largest image decoded: 64 Mpixels (256 MiB of RGBA8), well above any GPU texture limit.
constexpr uint64_t kMaxImagePixels = uint64_t(1) << 26;

}  // namespace fovea::scene::gltf
