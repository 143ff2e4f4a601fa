#include "core/scene/gltf/GltfDocument.h"

#include <cstring>
#include <fstream>
#include <string_view>

#include "core/util/Error.h"
#include "core/util/JsonUtil.h"

namespace fovea::scene::gltf {

namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;   // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
constexpr size_t kGlbHeaderBytes = 12;
constexpr size_t kChunkHeaderBytes = 8;

uint32_t readU32(const std::vector<uint8_t>& bytes, size_t offset) {
    // GLB is little-endian, as is every machine fovea targets; memcpy keeps unaligned reads legal.
    uint32_t value = 0;
    std::memcpy(&value, bytes.data() + offset, sizeof(value));
    return value;
}

std::string hexOffset(size_t offset) {
    return "byte " + std::to_string(offset);
}

struct GlbChunks {
    std::string json;
    std::optional<std::vector<uint8_t>> bin;
};

// The container rules of glTF 2.0 §4.4: header, then a non-empty JSON chunk first, then at most
// one BIN chunk second; chunks of unknown type after those are skipped, as the spec asks. Bytes
// after the length the header declares are ignored (with a warning), as the validator does.
GlbChunks splitGlb(std::vector<uint8_t> bytes, const std::string& file,
                   std::vector<std::string>& warnings) {
    auto fail = [&](const std::string& message) -> InputError {
        return InputError(file, "", "invalid GLB: " + message);
    };
    if (bytes.size() < kGlbHeaderBytes) {
        throw fail("the file is " + std::to_string(bytes.size()) +
                   " bytes, shorter than the 12-byte GLB header");
    }
    uint32_t version = readU32(bytes, 4);
    uint32_t length = readU32(bytes, 8);
    if (version != 2) throw fail("container version " + std::to_string(version) + " (expected 2)");
    if (length > bytes.size() || length < kGlbHeaderBytes) {
        throw fail("header length " + std::to_string(length) + " does not fit the file size " +
                   std::to_string(bytes.size()));
    }
    if (length < bytes.size()) {
        warnings.push_back("GLB: " + std::to_string(bytes.size() - length) +
                           " bytes after the declared length " + std::to_string(length) +
                           " are ignored");
        bytes.resize(length);
    }
    GlbChunks chunks;
    bool haveJson = false;
    size_t offset = kGlbHeaderBytes;
    size_t index = 0;
    while (offset < bytes.size()) {
        if (bytes.size() - offset < kChunkHeaderBytes) {
            throw fail("truncated chunk header at " + hexOffset(offset));
        }
        uint32_t chunkLength = readU32(bytes, offset);
        uint32_t chunkType = readU32(bytes, offset + 4);
        size_t dataStart = offset + kChunkHeaderBytes;
        if (chunkLength % 4 != 0) {
            throw fail("chunk " + std::to_string(index) + " length " + std::to_string(chunkLength) +
                       " is not a multiple of 4");
        }
        if (uint64_t(chunkLength) > uint64_t(bytes.size() - dataStart)) {
            throw fail("chunk " + std::to_string(index) + " (" + std::to_string(chunkLength) +
                       " bytes at " + hexOffset(dataStart) + ") runs past the end of the file");
        }
        if (index == 0 && chunkType != kChunkJson) {
            throw fail("the first chunk must be JSON");
        }
        if (chunkType == kChunkJson) {
            if (haveJson) throw fail("more than one JSON chunk");
            if (chunkLength == 0) throw fail("the JSON chunk is empty");
            chunks.json.assign(reinterpret_cast<const char*>(bytes.data() + dataStart),
                               chunkLength);
            haveJson = true;
        } else if (chunkType == kChunkBin) {
            if (chunks.bin) throw fail("more than one BIN chunk");
            if (index != 1) throw fail("the BIN chunk must directly follow the JSON chunk");
            chunks.bin.emplace(bytes.begin() + std::ptrdiff_t(dataStart),
                               bytes.begin() + std::ptrdiff_t(dataStart + chunkLength));
        }
        offset = dataStart + chunkLength;
        ++index;
    }
    if (!haveJson) throw fail("no JSON chunk");
    return chunks;
}

}  // namespace

GltfDocument readGltfDocument(const std::filesystem::path& path) {
    GltfDocument doc;
    doc.file = path.string();
    doc.baseDir = path.parent_path();
    std::vector<uint8_t> bytes;
    std::string error;
    if (!readRegularFile(path, kMaxGltfFileBytes, bytes, error)) {
        throw InputError(doc.file, "", "cannot read the glTF file: " + error);
    }
    std::string jsonText;
    if (bytes.size() >= 4 && readU32(bytes, 0) == kGlbMagic) {
        GlbChunks chunks = splitGlb(std::move(bytes), doc.file, doc.warnings);
        doc.isGlb = true;
        doc.glbBin = std::move(chunks.bin);
        jsonText = std::move(chunks.json);
    } else {
        std::string extension = path.extension().string();
        if (extension == ".glb" || extension == ".GLB") {
            throw InputError(doc.file, "", "invalid GLB: the file does not start with 'glTF'");
        }
        jsonText.assign(bytes.begin(), bytes.end());
    }
    if (jsonText.empty()) throw InputError(doc.file, "", "the file is empty");
    // glTF 2.0 §3.2: JSON "MUST NOT" start with a byte order mark; nlohmann would skip it.
    if (jsonText.size() >= 3 && uint8_t(jsonText[0]) == 0xEF && uint8_t(jsonText[1]) == 0xBB &&
        uint8_t(jsonText[2]) == 0xBF) {
        throw InputError(doc.file, "", "the JSON starts with a byte order mark (not allowed)");
    }
    try {
        doc.json = parseJsonText(jsonText, doc.file);
    } catch (const nlohmann::json::exception& e) {
        // parseJsonText reports syntax errors itself; nlohmann still throws out_of_range for
        // numbers beyond double (1e309), which is bad input like any other.
        std::string what = e.what();
        if (size_t bracket = what.find("] "); bracket != std::string::npos) {
            what.erase(0, bracket + 2);
        }
        throw InputError(doc.file, "", "invalid JSON: " + what);
    }
    if (!doc.json.is_object()) {
        throw InputError(doc.file, "",
                         "the glTF JSON must be an object, got " + jsonTypeName(doc.json));
    }
    return doc;
}

bool uriLeavesFolder(const std::string& decoded) {
    const std::filesystem::path path(decoded);
    if (path.is_absolute() || path.has_root_name() || path.has_root_directory()) return true;
    const std::filesystem::path normal = path.lexically_normal();
    return !normal.empty() && *normal.begin() == "..";
}

std::string externalUriMessage(const std::string& uri) {
    return "'" + truncateForMessage(uri, 120) +
           "' refers to a file outside the scene's folder; not read (pass --allow-external-uris "
           "to allow it)";
}

}  // namespace fovea::scene::gltf
