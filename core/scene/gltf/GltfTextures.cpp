#include "core/scene/gltf/GltfTextures.h"

#include <memory>

#include "core/scene/gltf/GltfLayout.h"
#include "core/util/Error.h"

// stb_image from Debian's libstb-dev lives under <stb/>. Compiled here with static linkage so no
// other library's copy of stb can clash with it; only this file decodes images.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wunused-function"
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_NO_STDIO
#define STBI_FAILURE_USERMSG
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace fovea::scene::gltf {

namespace {

std::string imagePointer(size_t index) {
    return "/images/" + std::to_string(index);
}

// The bytes of buffer `index` straight from the document (for images of unused buffers, which
// tinygltf did not load): the GLB BIN chunk, a data URI or a file.
bool rawBufferBytes(const GltfDocument& doc, uint64_t index, std::vector<uint8_t>& out,
                    std::string& error) {
    const Json* buffers = doc.json.contains("buffers") ? &doc.json.at("buffers") : nullptr;
    if (!buffers || !buffers->is_array() || index >= buffers->size() ||
        !(*buffers)[index].is_object()) {
        error = "buffer " + std::to_string(index) + " does not exist";
        return false;
    }
    JsonView buffer(&(*buffers)[index], "", nullptr);
    std::optional<std::string> uri = buffer.string("uri");
    if (!uri) {
        if (!doc.glbBin) {
            error = "no GLB BIN chunk";
            return false;
        }
        out = *doc.glbBin;
        return true;
    }
    if (uri->rfind("data:", 0) == 0) {
        size_t comma = uri->find(',');
        if (comma == std::string::npos || !base64Decode(uri->substr(comma + 1), out)) {
            error = "invalid data URI";
            return false;
        }
        return true;
    }
    std::string decoded;
    if (!percentDecode(*uri, decoded)) {
        error = "malformed URI";
        return false;
    }
    if (!doc.allowExternalUris && uriLeavesFolder(decoded)) {
        error = externalUriMessage(*uri);
        return false;
    }
    return readRegularFile(doc.baseDir / decoded, kMaxGltfFileBytes, out, error);
}

// The encoded bytes of image `index`. `model` supplies loaded buffers of used images (may be
// null for unused ones).
bool encodedImage(const GltfDocument& doc, const tinygltf::Model* model, size_t index,
                  std::vector<uint8_t>& out, std::string& error) {
    const Json& image = doc.json.at("images").at(index);
    JsonView view(&image, imagePointer(index), nullptr);
    if (std::optional<std::string> uri = view.string("uri")) {
        if (uri->rfind("data:", 0) == 0) {
            size_t comma = uri->find(',');
            if (comma == std::string::npos || !base64Decode(uri->substr(comma + 1), out)) {
                error = "invalid data URI";
                return false;
            }
            return true;
        }
        std::string decoded;
        if (!percentDecode(*uri, decoded) || decoded.empty()) {
            error = "malformed URI";
            return false;
        }
        if (!doc.allowExternalUris && uriLeavesFolder(decoded)) {
            error = externalUriMessage(*uri);
            return false;
        }
        std::filesystem::path path = doc.baseDir / decoded;
        if (!readRegularFile(path, kMaxImageFileBytes, out, error)) {
            error = path.string() + ": " + error;
            return false;
        }
        return true;
    }
    std::optional<uint64_t> viewIndex = view.uint("bufferView");
    const Json* views = doc.json.contains("bufferViews") ? &doc.json.at("bufferViews") : nullptr;
    if (!viewIndex || !views || !views->is_array() || *viewIndex >= views->size()) {
        error = "no image source";
        return false;
    }
    JsonView bufferView(&(*views)[*viewIndex], "", nullptr);
    uint64_t offset = bufferView.uint("byteOffset").value_or(0);
    uint64_t length = bufferView.uint("byteLength").value_or(0);
    std::optional<uint64_t> bufferIndex = bufferView.uint("buffer");
    std::vector<uint8_t> raw;
    const std::vector<uint8_t>* data = nullptr;
    if (model && bufferIndex && *bufferIndex < model->buffers.size() &&
        !model->buffers[*bufferIndex].data.empty()) {
        data = &model->buffers[*bufferIndex].data;
    } else if (bufferIndex && rawBufferBytes(doc, *bufferIndex, raw, error)) {
        data = &raw;
    } else {
        if (error.empty()) error = "no buffer";
        return false;
    }
    uint64_t end = 0;
    if (length == 0 || length > kMaxImageFileBytes || !mulAdd(1, offset, length, end) ||
        end > data->size()) {
        error = "bufferView " + std::to_string(*viewIndex) + " lies outside its buffer";
        return false;
    }
    out.assign(data->begin() + std::ptrdiff_t(offset), data->begin() + std::ptrdiff_t(end));
    return true;
}

std::string stbReason() {
    const char* reason = stbi_failure_reason();
    return reason ? reason : "unknown error";
}

// Header check shared by decoding and probing.
bool inspect(const std::vector<uint8_t>& bytes, int& width, int& height, std::string& error) {
    int components = 0;
    if (bytes.empty() || bytes.size() > kMaxImageFileBytes ||
        !stbi_info_from_memory(bytes.data(), int(bytes.size()), &width, &height, &components)) {
        error =
            "not a decodable image (" + (bytes.empty() ? std::string("empty") : stbReason()) + ")";
        return false;
    }
    if (width <= 0 || height <= 0 || uint64_t(width) * uint64_t(height) > kMaxImagePixels) {
        error = "image size " + std::to_string(width) + "x" + std::to_string(height) +
                " is not supported";
        return false;
    }
    return true;
}

}  // namespace

bool base64Decode(const std::string& text, std::vector<uint8_t>& out) {
    auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        if (c == '+') return 62;
        if (c == '/') return 63;
        return -1;
    };
    if (text.size() % 4 != 0) return false;
    out.clear();
    out.reserve(text.size() / 4 * 3);
    for (size_t i = 0; i < text.size(); i += 4) {
        int v[4];
        size_t padding = 0;
        for (size_t k = 0; k < 4; ++k) {
            char c = text[i + k];
            if (c == '=' && i + 4 == text.size() && k >= 2) {
                v[k] = 0;
                ++padding;
            } else {
                v[k] = value(c);
                if (v[k] < 0 || padding > 0) return false;
            }
        }
        uint32_t word =
            uint32_t(v[0]) << 18 | uint32_t(v[1]) << 12 | uint32_t(v[2]) << 6 | uint32_t(v[3]);
        out.push_back(uint8_t(word >> 16));
        if (padding < 2) out.push_back(uint8_t(word >> 8));
        if (padding < 1) out.push_back(uint8_t(word));
    }
    return true;
}

Texture decodeImage(const GltfDocument& doc, const tinygltf::Model& model, size_t index) {
    std::vector<uint8_t> bytes;
    std::string error;
    auto fail = [&](const std::string& message) {
        return InputError(doc.file, imagePointer(index), message);
    };
    if (!encodedImage(doc, &model, index, bytes, error)) throw fail(error);
    int width = 0, height = 0;
    if (!inspect(bytes, width, height, error)) throw fail(error);
    Texture texture;
    JsonView image(&doc.json.at("images").at(index), "", nullptr);
    texture.name = image.string("name").value_or(image.string("uri").value_or(""));
    if (texture.name.empty() || texture.name.rfind("data:", 0) == 0) {
        texture.name = "image " + std::to_string(index);
    }
    int w = 0, h = 0, components = 0;
    const auto* data = bytes.data();
    int size = int(bytes.size());
    if (stbi_is_16_bit_from_memory(data, size)) {
        std::unique_ptr<stbi_us, void (*)(void*)> pixels(
            stbi_load_16_from_memory(data, size, &w, &h, &components, 4), &stbi_image_free);
        if (!pixels || w != width || h != height) throw fail("decoding failed: " + stbReason());
        texture.rgba8.resize(size_t(w) * size_t(h) * 4);
        for (size_t i = 0; i < texture.rgba8.size(); ++i) {
            texture.rgba8[i] = uint8_t((uint32_t(pixels.get()[i]) * 255u + 32767u) / 65535u);
        }
    } else {
        std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
            stbi_load_from_memory(data, size, &w, &h, &components, 4), &stbi_image_free);
        if (!pixels || w != width || h != height) throw fail("decoding failed: " + stbReason());
        texture.rgba8.assign(pixels.get(), pixels.get() + size_t(w) * size_t(h) * 4);
    }
    texture.width = uint32_t(w);
    texture.height = uint32_t(h);
    return texture;
}

void probeUnusedImages(const GltfDocument& doc, const GltfUsage& usage,
                       std::vector<std::string>& warnings) {
    for (size_t i = 0; i < usage.images.size(); ++i) {
        if (usage.images[i] || !doc.json.at("images").at(i).is_object()) continue;
        std::vector<uint8_t> bytes;
        std::string error;
        int width = 0, height = 0;
        if (!encodedImage(doc, nullptr, i, bytes, error) || !inspect(bytes, width, height, error)) {
            warnings.push_back(imagePointer(i) + ": " + error + " (unused, ignored)");
        }
    }
}

}  // namespace fovea::scene::gltf
