#include "core/scene/gltf/GltfTiny.h"

#include <cctype>
#include <cmath>
#include <cstring>

#include "core/util/Error.h"

namespace fovea::scene::gltf {

namespace {

// Replaces the entities of `collection` that the scene does not use by `stub`.
void stubUnused(Json& root, const char* collection, const std::vector<char>& used,
                const Json& stub) {
    auto it = root.find(collection);
    if (it == root.end() || !it->is_array()) return;
    for (size_t i = 0; i < it->size(); ++i) {
        if (i >= used.size() || !used[i]) (*it)[i] = stub;
    }
}

// tinygltf reads integers only from JSON integers; glTF allows 3.0 for 3 (the validator agrees).
void normalizeIntegers(Json& value) {
    if (value.is_number_float()) {
        double d = value.get<double>();
        if (std::isfinite(d) && std::floor(d) == d && std::fabs(d) <= double(kMaxJsonInteger)) {
            // Non-negative values must become JSON unsigned: tinygltf reads counts, offsets and
            // lengths only from those.
            if (d >= 0.0) {
                value = uint64_t(d);
            } else {
                value = int64_t(d);
            }
        }
    } else if (value.is_array() || value.is_object()) {
        for (Json& child : value) normalizeIntegers(child);
    }
}

// Keeps only what fovea reads from a rendered primitive (tinygltf parses every attribute).
void pruneMeshes(Json& root, const GltfUsage& usage) {
    auto meshes = root.find("meshes");
    if (meshes == root.end() || !meshes->is_array()) return;
    for (size_t m = 0; m < meshes->size() && m < usage.primitives.size(); ++m) {
        Json& mesh = (*meshes)[m];
        if (!mesh.is_object()) continue;
        mesh.erase("weights");
        auto prims = mesh.find("primitives");
        if (prims == mesh.end() || !prims->is_array()) continue;
        for (size_t p = 0; p < prims->size(); ++p) {
            bool rendered = p < usage.primitives[m].size() && usage.primitives[m][p];
            Json& prim = (*prims)[p];
            if (!rendered) {
                prim = Json{{"attributes", Json::object()}, {"mode", 0}};
                continue;
            }
            prim.erase("targets");
            // fovea reads the indices itself (GltfMesh.cpp); tinygltf rejects an indices
            // accessor without buffer view, which glTF allows (all zeros).
            prim.erase("indices");
            Json& attributes = prim["attributes"];
            for (auto it = attributes.begin(); it != attributes.end();) {
                const std::string& key = it.key();
                it = (key == "POSITION" || key == "NORMAL" || key == "TEXCOORD_0" ||
                      key == "COLOR_0" || key == "TANGENT")
                         ? std::next(it)
                         : attributes.erase(it);
            }
        }
    }
}

// `path` percent-encoded so that tinygltf's decoder (which also turns '+' into a space) gives it
// back byte for byte: every byte outside [A-Za-z0-9/._-] becomes %XX.
std::string encodeForTinygltf(const std::string& path) {
    static const char* kHex = "0123456789ABCDEF";
    std::string out;
    for (unsigned char c : path) {
        if (std::isalnum(c) || c == '/' || c == '.' || c == '_' || c == '-') {
            out += char(c);
        } else {
            out += '%';
            out += kHex[c >> 4];
            out += kHex[c & 15];
        }
    }
    return out;
}

// tinygltf joins every buffer URI to its base folder as text ("/scene" + "/" + "/abs/x.bin"), so
// an absolute URI allowed by --allow-external-uris was never found. Every used file URI is handed
// over as an absolute path instead (validated and decoded by fovea) with an empty base folder.
void absoluteBufferUris(Json& root, const GltfDocument& doc, const GltfUsage& usage) {
    auto buffers = root.find("buffers");
    if (buffers == root.end() || !buffers->is_array()) return;
    std::error_code ec;
    std::filesystem::path base = std::filesystem::absolute(doc.baseDir, ec);
    if (ec) base = doc.baseDir;
    for (size_t b = 0; b < buffers->size() && b < usage.buffers.size(); ++b) {
        if (!usage.buffers[b] || !(*buffers)[b].is_object()) continue;
        auto uri = (*buffers)[b].find("uri");
        if (uri == (*buffers)[b].end() || !uri->is_string()) continue;
        const std::string& text = uri->get_ref<const std::string&>();
        std::string decoded;
        if (text.rfind("data:", 0) == 0 || !percentDecode(text, decoded)) continue;
        if (!doc.allowExternalUris && uriLeavesFolder(decoded)) {  // validation refused it first
            throw InputError(doc.file, "/buffers/" + std::to_string(b) + "/uri",
                             externalUriMessage(text));
        }
        *uri = encodeForTinygltf((base / decoded).lexically_normal().string());
    }
}

Json prunedJson(const GltfDocument& doc, const GltfUsage& usage) {
    Json root = doc.json;
    root.erase("animations");
    root.erase("skins");
    root.erase("scene");
    if (auto scenes = root.find("scenes"); scenes != root.end() && scenes->is_array()) {
        for (Json& scene : *scenes) scene = Json{{"nodes", Json::array()}};
    }
    stubUnused(root, "nodes", usage.nodes, Json::object());
    stubUnused(root, "meshes", usage.meshes, Json{{"primitives", Json::array()}});
    stubUnused(root, "accessors", usage.accessors,
               Json{{"componentType", 5126}, {"count", 1}, {"type", "SCALAR"}});
    stubUnused(root, "bufferViews", usage.bufferViews, Json{{"buffer", 0}, {"byteLength", 1}});
    stubUnused(root, "buffers", usage.buffers,
               Json{{"byteLength", 1}, {"uri", "data:application/octet-stream;base64,AA=="}});
    stubUnused(root, "materials", usage.materials, Json::object());
    stubUnused(root, "textures", usage.textures, Json::object());
    stubUnused(root, "samplers", usage.samplers, Json::object());
    stubUnused(root, "cameras", usage.cameras,
               Json{{"type", "perspective"}, {"perspective", {{"yfov", 1}, {"znear", 1}}}});
    if (auto ext = root.find("extensions"); ext != root.end() && ext->is_object()) {
        if (auto khr = ext->find("KHR_lights_punctual"); khr != ext->end() && khr->is_object()) {
            stubUnused(*khr, "lights", usage.lights, Json{{"type", "point"}});
        }
    }
    pruneMeshes(root, usage);
    absoluteBufferUris(root, doc, usage);
    // fovea reads and decodes images itself (GltfTextures.cpp); tinygltf only keeps the count.
    if (auto images = root.find("images"); images != root.end() && images->is_array()) {
        for (Json& image : *images) image = Json{{"uri", ""}};
    }
    normalizeIntegers(root);
    return root;
}

// Images reach tinygltf without data (see prunedJson); this loader only satisfies its API.
bool ignoreImage(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                 const unsigned char*, int, void*) {
    return true;
}

bool fileExists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::is_regular_file(path, ec);
}

std::string expandPath(const std::string& path, void*) {
    return path;
}

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void*) {
    std::string error;
    if (!readRegularFile(path, kMaxGltfFileBytes, *out, error)) {
        if (err) *err += error;
        return false;
    }
    return true;
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&,
                    void*) {
    if (err) *err += "fovea never writes glTF files";
    return false;
}

// A GLB holding exactly the pruned JSON and the BIN chunk, laid out as tinygltf expects.
std::vector<unsigned char> buildGlb(const std::string& json, const std::vector<uint8_t>* bin) {
    std::string text = json;
    while (text.size() % 4) text += ' ';
    bool withBin = bin && !bin->empty();
    uint64_t total = 12 + 8 + text.size() + (withBin ? 8 + bin->size() : 0);
    std::vector<unsigned char> out;
    out.reserve(size_t(total));
    auto put32 = [&](uint32_t v) {
        unsigned char b[4];
        std::memcpy(b, &v, 4);
        out.insert(out.end(), b, b + 4);
    };
    put32(0x46546C67);
    put32(2);
    put32(uint32_t(total));
    put32(uint32_t(text.size()));
    put32(0x4E4F534A);
    out.insert(out.end(), text.begin(), text.end());
    if (withBin) {
        put32(uint32_t(bin->size()));
        put32(0x004E4942);
        out.insert(out.end(), bin->begin(), bin->end());
    }
    return out;
}

}  // namespace

tinygltf::Model loadTinyGltf(const GltfDocument& doc, const GltfUsage& usage) {
    std::string json = prunedJson(doc, usage).dump(-1, ' ', false, Json::error_handler_t::replace);
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(&ignoreImage, nullptr);
    loader.SetFsCallbacks(
        tinygltf::FsCallbacks{&fileExists, &expandPath, &readWholeFile, &writeWholeFile, nullptr});
    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
    const std::string base;  // every used file URI is absolute (absoluteBufferUris)
    try {
        if (doc.isGlb) {
            std::vector<unsigned char> glb = buildGlb(json, doc.glbBin ? &*doc.glbBin : nullptr);
            if (glb.size() > kMaxGltfFileBytes) {
                throw InputError(doc.file, "", "the GLB is too large for tinygltf");
            }
            ok = loader.LoadBinaryFromMemory(&model, &err, &warn, glb.data(), unsigned(glb.size()),
                                             base);
        } else {
            ok = loader.LoadASCIIFromString(&model, &err, &warn, json.data(), unsigned(json.size()),
                                            base);
        }
    } catch (const InputError&) {
        throw;
    } catch (const std::exception& e) {
        throw InputError(doc.file, "", std::string("tinygltf failed: ") + e.what());
    }
    if (!ok) {
        while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
        throw InputError(doc.file, "", "tinygltf: " + (err.empty() ? "load failed" : err));
    }
    for (size_t b = 0; b < usage.buffers.size() && b < model.buffers.size(); ++b) {
        if (!usage.buffers[b]) continue;
        JsonView buffer(&doc.json.at("buffers").at(b), "/buffers/" + std::to_string(b), nullptr);
        uint64_t declared = buffer.uint("byteLength").value_or(0);
        if (model.buffers[b].data.size() != declared) {
            throw InputError(doc.file, buffer.pointer(),
                             "loaded " + std::to_string(model.buffers[b].data.size()) +
                                 " bytes, byteLength says " + std::to_string(declared));
        }
    }
    return model;
}

}  // namespace fovea::scene::gltf
