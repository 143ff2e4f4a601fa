// Buffers, buffer views, accessors and attribute formats (see GltfValidate.h).
#include <filesystem>

#include "core/scene/gltf/GltfLayout.h"
#include "core/scene/gltf/GltfUsage.h"
#include "core/scene/gltf/GltfValidate.h"

namespace fovea::scene::gltf {

namespace {

constexpr uint64_t kMaxStride = 252;  // glTF 2.0 bufferView.byteStride maximum

// The declared byteLength of a buffer, read silently (its own checks report problems).
std::optional<uint64_t> bufferLength(const GltfJson& gltf, uint64_t index) {
    if (index >= gltf.count("buffers")) return std::nullopt;
    return gltf.entity("buffers", index).silent().uint("byteLength");
}

struct ViewInfo {
    uint64_t offset = 0, length = 0, stride = 0;  // stride 0 = tightly packed
};

// A buffer view whose own properties are sound (they are checked and reported separately).
std::optional<ViewInfo> viewInfo(const GltfJson& gltf, std::optional<uint64_t> index) {
    if (!index || *index >= gltf.count("bufferViews")) return std::nullopt;
    JsonView view = gltf.entity("bufferViews", *index).silent();
    std::optional<uint64_t> length = view.uint("byteLength");
    if (!length || *length == 0) return std::nullopt;
    ViewInfo info;
    info.offset = view.uint("byteOffset").value_or(0);
    info.length = *length;
    info.stride = view.uint("byteStride").value_or(0);
    return info;
}

void validateBuffer(const GltfJson& gltf, const GltfDocument& doc, size_t index) {
    JsonView buffer = gltf.entity("buffers", index);
    if (!buffer.isObject()) return;
    buffer.require("byteLength");
    std::optional<uint64_t> length = buffer.uint("byteLength");
    if (length && *length == 0) buffer.issueAt("byteLength", "must be at least 1");
    std::optional<std::string> uri = buffer.string("uri");
    if (!buffer.has("uri")) {
        if (!doc.isGlb) {
            buffer.issue("has no 'uri' and the file is not a GLB: its data is not available");
        } else if (index != 0) {
            buffer.issue("has no 'uri'; only buffer 0 can refer to the GLB's BIN chunk");
        } else if (!doc.glbBin) {
            buffer.issue("refers to the GLB's BIN chunk, but the file has none");
        } else if (length && (*length > doc.glbBin->size() || doc.glbBin->size() - *length > 3)) {
            // The BIN chunk may only add the up-to-3 padding bytes of §4.4.3.3.
            buffer.issueAt("byteLength", "is " + std::to_string(*length) +
                                             " but the BIN chunk holds " +
                                             std::to_string(doc.glbBin->size()) + " bytes");
        }
        return;
    }
    if (!uri || !length) return;
    if (uri->rfind("data:", 0) == 0) {
        size_t comma = uri->find(',');
        std::string header = uri->substr(0, comma == std::string::npos ? 0 : comma + 1);
        if (header != "data:application/octet-stream;base64," &&
            header != "data:application/gltf-buffer;base64,") {
            buffer.issueAt("uri",
                           "unsupported data URI (expected "
                           "data:application/octet-stream;base64,)");
            return;
        }
        uint64_t size = 0;
        if (!base64DecodedSize(uri->substr(comma + 1), size)) {
            buffer.issueAt("uri", "the data URI is not valid base64");
        } else if (size != *length) {
            buffer.issueAt("byteLength", "is " + std::to_string(*length) +
                                             " but the data URI holds " + std::to_string(size) +
                                             " bytes");
        }
        return;
    }
    if (hasUriScheme(*uri)) {
        buffer.issueAt("uri", "unsupported URI '" + uri->substr(0, 60) +
                                  "' (only relative paths and data URIs are loaded)");
        return;
    }
    std::string decoded;
    if (!percentDecode(*uri, decoded) || decoded.empty()) {
        buffer.issueAt("uri", "malformed URI");
        return;
    }
    if (!doc.allowExternalUris && uriLeavesFolder(decoded)) {
        buffer.issueAt("uri", externalUriMessage(*uri));
        return;
    }
    std::filesystem::path file = doc.baseDir / decoded;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) {
        buffer.issueAt("uri", "file not found: " + file.string());
        return;
    }
    uint64_t size = std::filesystem::file_size(file, ec);
    if (ec || size != *length) {
        buffer.issueAt("byteLength", "is " + std::to_string(*length) + " but " + file.string() +
                                         " has " + std::to_string(size) + " bytes");
    }
}

void validateBufferView(const GltfJson& gltf, size_t index) {
    JsonView view = gltf.entity("bufferViews", index);
    if (!view.isObject()) return;
    view.require("buffer");
    view.require("byteLength");
    std::optional<uint64_t> length = view.uint("byteLength");
    std::optional<uint64_t> offset = view.uint("byteOffset");
    if (length && *length == 0) view.issueAt("byteLength", "must be at least 1");
    std::optional<uint64_t> stride = view.uint("byteStride");
    if (stride && (*stride < 4 || *stride > kMaxStride || *stride % 4 != 0)) {
        view.issueAt("byteStride",
                     "must be a multiple of 4 in [4, 252], got " + std::to_string(*stride));
    }
    std::optional<uint64_t> target = view.uint("target");
    if (target && *target != kTargetArrayBuffer && *target != kTargetElementArrayBuffer) {
        view.issueAt("target", "invalid target " + std::to_string(*target));
    }
    if (target && *target == kTargetElementArrayBuffer && stride) {
        view.issueAt("byteStride", "an index buffer view must not have a byteStride");
    }
    std::optional<uint64_t> buffer = view.silent().uint("buffer");
    std::optional<uint64_t> bufferBytes = buffer ? bufferLength(gltf, *buffer) : std::nullopt;
    uint64_t end = 0;
    if (length && bufferBytes &&
        (!mulAdd(1, offset.value_or(0), *length, end) || end > *bufferBytes)) {
        view.issueAt("byteLength", "byteOffset " + std::to_string(offset.value_or(0)) +
                                       " + byteLength " + std::to_string(*length) +
                                       " exceeds buffer " + std::to_string(*buffer) + " (" +
                                       std::to_string(*bufferBytes) + " bytes)");
    }
}

// Checks that [offset, offset + span) of buffer view `view` is inside it and that the data is
// aligned to its component size (§3.6.2.4).
void checkRange(const JsonView& owner, const GltfJson& gltf, std::optional<uint64_t> viewIndex,
                uint64_t offset, uint64_t span, uint64_t component, const std::string& what) {
    std::optional<ViewInfo> view = viewInfo(gltf, viewIndex);
    if (!view) return;
    uint64_t end = 0;
    if (!mulAdd(1, offset, span, end) || end > view->length) {
        owner.issue(what + " needs bytes [" + std::to_string(offset) + ", " +
                    (end ? std::to_string(end) : std::string("overflow")) + ") of bufferView " +
                    std::to_string(*viewIndex) + ", which has " + std::to_string(view->length));
    }
    if (component && (offset % component != 0 || (view->offset + offset) % component != 0)) {
        owner.issue(what + " is not aligned to its " + std::to_string(component) +
                    "-byte components");
    }
}

void validateSparse(const GltfJson& gltf, const JsonView& accessor, uint64_t count,
                    uint64_t element) {
    JsonView sparse = accessor.object("sparse");
    if (!sparse.isObject()) return;
    for (const char* key : {"count", "indices", "values"}) sparse.require(key);
    std::optional<uint64_t> n = sparse.uint("count");
    if (n && (*n == 0 || *n > count)) {
        sparse.issueAt("count", "must be in [1, accessor count " + std::to_string(count) + "]");
        return;
    }
    JsonView indices = sparse.object("indices"), values = sparse.object("values");
    indices.require("bufferView");
    indices.require("componentType");
    values.require("bufferView");
    std::optional<uint64_t> type = indices.uint("componentType");
    if (type && *type != kUnsignedByte && *type != kUnsignedShort && *type != kUnsignedInt) {
        indices.issueAt("componentType", "sparse indices must be unsigned byte, short or int");
        return;
    }
    for (const JsonView* part : {&indices, &values}) {
        std::optional<uint64_t> view = part->silent().uint("bufferView");
        if (view && *view < gltf.count("bufferViews") &&
            gltf.entity("bufferViews", *view).silent().has("byteStride")) {
            part->issueAt("bufferView",
                          "a sparse accessor's buffer view must not have a "
                          "byteStride");
        }
    }
    if (!n || !type || element == 0) return;
    uint64_t indexBytes = componentBytes(*type), span = 0;
    if (mulAdd(*n, indexBytes, 0, span)) {
        checkRange(indices, gltf, indices.silent().uint("bufferView"),
                   indices.uint("byteOffset").value_or(0), span, indexBytes, "sparse indices");
    }
    if (mulAdd(*n, element, 0, span)) {
        uint64_t component = componentBytes(accessor.silent().uint("componentType").value_or(0));
        checkRange(values, gltf, values.silent().uint("bufferView"),
                   values.uint("byteOffset").value_or(0), span, component, "sparse values");
    }
}

void validateAccessor(const GltfJson& gltf, size_t index) {
    JsonView accessor = gltf.entity("accessors", index);
    if (!accessor.isObject()) return;
    for (const char* key : {"componentType", "count", "type"}) accessor.require(key);
    std::optional<uint64_t> componentType = accessor.uint("componentType");
    std::optional<std::string> type = accessor.string("type");
    std::optional<uint64_t> count = accessor.uint("count");
    std::optional<bool> normalized = accessor.boolean("normalized");
    std::optional<uint64_t> offset = accessor.uint("byteOffset");
    if (componentType && componentBytes(*componentType) == 0) {
        accessor.issueAt("componentType",
                         "invalid componentType " + std::to_string(*componentType));
    }
    if (type && typeComponents(*type) == 0) {
        accessor.issueAt("type", "invalid type '" + *type + "'");
    }
    if (count && *count == 0) accessor.issueAt("count", "must be at least 1");
    if (normalized && *normalized && componentType &&
        (*componentType == kFloat || *componentType == kUnsignedInt)) {
        accessor.issueAt("normalized", "only byte and short components can be normalized");
    }
    if (offset && !accessor.has("bufferView")) {
        accessor.issueAt("byteOffset", "has no meaning without a bufferView");
    }
    if (!componentType || !type || !count) return;
    uint64_t component = componentBytes(*componentType);
    uint64_t element = elementBytes(*type, *componentType);
    if (element == 0 || *count == 0) return;
    validateSparse(gltf, accessor, *count, element);
    std::optional<uint64_t> viewIndex = accessor.silent().uint("bufferView");
    std::optional<ViewInfo> view = viewInfo(gltf, viewIndex);
    if (!view) return;
    if (view->stride && view->stride < element) {
        accessor.issue("bufferView " + std::to_string(*viewIndex) + " byteStride " +
                       std::to_string(view->stride) + " is smaller than the element size " +
                       std::to_string(element));
        return;
    }
    uint64_t span = 0;
    if (!accessorSpan(*count, view->stride ? view->stride : element, element, span)) {
        accessor.issueAt("count", "count " + std::to_string(*count) + " overflows");
        return;
    }
    uint64_t end = 0;
    if (!mulAdd(1, offset.value_or(0), span, end) || end > view->length) {
        accessor.issueAt("count", std::to_string(*count) + " elements from byteOffset " +
                                      std::to_string(offset.value_or(0)) + " need " +
                                      std::to_string(end) + " bytes, but bufferView " +
                                      std::to_string(*viewIndex) + " has " +
                                      std::to_string(view->length));
    }
    if (offset.value_or(0) % component != 0 || (view->offset + offset.value_or(0)) % component) {
        accessor.issueAt("byteOffset", "is not aligned to the " + std::to_string(component) +
                                           "-byte component size");
    }
}

// The formats glTF 2.0 §3.7.2.1 allows for the attributes fovea reads; KHR_mesh_quantization
// widens them.
bool allowedFormat(const std::string& semantic, const std::string& type, uint64_t componentType,
                   bool normalized, bool quantized) {
    bool isFloat = componentType == kFloat;
    bool small = componentType == kByte || componentType == kUnsignedByte ||
                 componentType == kShort || componentType == kUnsignedShort;
    if (semantic == "POSITION") return type == "VEC3" && (isFloat || (quantized && small));
    if (semantic == "NORMAL") {
        return type == "VEC3" && (isFloat || (quantized && normalized &&
                                              (componentType == kByte || componentType == kShort)));
    }
    if (semantic == "TEXCOORD_0") {
        bool core =
            isFloat ||
            (normalized && (componentType == kUnsignedByte || componentType == kUnsignedShort));
        return type == "VEC2" && (core || (quantized && small));
    }
    if (semantic == "TANGENT") {  // §3.7.2.1 VEC4 float; quantized: normalized byte/short
        return type == "VEC4" && (isFloat || (quantized && normalized &&
                                              (componentType == kByte || componentType == kShort)));
    }
    if (semantic == "COLOR_0") {  // §3.7.2.1: float, or normalized unsigned byte/short
        return (type == "VEC3" || type == "VEC4") &&
               (isFloat || (normalized &&
                            (componentType == kUnsignedByte || componentType == kUnsignedShort)));
    }
    return true;
}

void validatePrimitive(const GltfJson& gltf, const JsonView& prim, bool quantized) {
    JsonView attributes = prim.silent().object("attributes");
    std::optional<uint64_t> vertexCount;
    for (const char* semantic : {"POSITION", "NORMAL", "TEXCOORD_0", "COLOR_0", "TANGENT"}) {
        std::optional<uint64_t> index = attributes.uint(semantic);
        if (!index || *index >= gltf.count("accessors")) continue;
        JsonView accessor = gltf.entity("accessors", *index).silent();
        std::optional<uint64_t> componentType = accessor.uint("componentType");
        std::optional<std::string> type = accessor.string("type");
        std::optional<uint64_t> count = accessor.uint("count");
        bool normalized = accessor.boolean("normalized").value_or(false);
        std::string pointer = prim.pointer() + "/attributes/" + semantic;
        if (!componentType || !type || !count) continue;
        if (!allowedFormat(semantic, *type, *componentType, normalized, quantized)) {
            gltf.issues().add(pointer, std::string("invalid format for ") + semantic + ": " +
                                           *type + " of componentType " +
                                           std::to_string(*componentType) +
                                           (normalized ? " (normalized)" : ""));
        }
        if (vertexCount && *count != *vertexCount) {
            gltf.issues().add(pointer, std::string(semantic) + " has " + std::to_string(*count) +
                                           " elements, POSITION has " +
                                           std::to_string(*vertexCount));
        }
        if (!vertexCount) vertexCount = count;
        std::optional<ViewInfo> view = viewInfo(gltf, accessor.uint("bufferView"));
        if (view && ((view->offset + accessor.uint("byteOffset").value_or(0)) % 4 != 0)) {
            gltf.issues().add(pointer, "vertex attribute data must start on a 4-byte boundary");
        }
    }
    std::optional<uint64_t> indices = prim.silent().uint("indices");
    if (indices && *indices < gltf.count("accessors")) {
        JsonView accessor = gltf.entity("accessors", *indices).silent();
        std::string pointer = prim.pointerTo("indices");
        std::optional<uint64_t> componentType = accessor.uint("componentType");
        if (accessor.string("type").value_or("SCALAR") != "SCALAR" ||
            (componentType && *componentType != kUnsignedByte && *componentType != kUnsignedShort &&
             *componentType != kUnsignedInt) ||
            accessor.boolean("normalized").value_or(false)) {
            gltf.issues().add(pointer, "indices must be SCALAR unsigned byte, short or int");
        }
        // Without a buffer view the indices are all zero (§3.6.2.1): degenerate but valid.
        std::optional<uint64_t> view = accessor.uint("bufferView");
        if (view && *view < gltf.count("bufferViews") &&
            gltf.entity("bufferViews", *view).silent().has("byteStride")) {
            gltf.issues().add(pointer, "the indices' buffer view must not have a byteStride");
        }
    }
    // A textured material needs texture coordinates (glTF 2.0 §3.9.2 texCoord).
    std::optional<uint64_t> material = prim.silent().uint("material");
    if (material && *material < gltf.count("materials") && !attributes.has("TEXCOORD_0")) {
        JsonView m = gltf.entity("materials", *material).silent();
        for (const TextureSlot& slot : renderedTextureSlots()) {
            JsonView info = (*slot.owner ? m.object(slot.owner) : m).object(slot.name);
            if (info.isObject() && effectiveTexCoord(info) == 0) {
                gltf.issues().add(prim.pointerTo("material"), std::string("material ") +
                                                                  std::to_string(*material) +
                                                                  " has a " + slot.name +
                                                                  " but the primitive has no "
                                                                  "TEXCOORD_0");
                break;
            }
        }
    }
}

void validateMeshes(const GltfJson& gltf, bool quantized) {
    for (size_t m = 0; m < gltf.count("meshes"); ++m) {
        JsonView mesh = gltf.entity("meshes", m);
        if (!mesh.isObject()) continue;
        mesh.require("primitives");
        JsonView primitives = mesh.array("primitives");
        if (mesh.has("primitives") && primitives.exists() && primitives.size() == 0) {
            mesh.issueAt("primitives", "must not be empty");
        }
        for (size_t p = 0; p < primitives.size(); ++p) {
            JsonView prim = primitives.element(p);
            if (!prim.isObject()) {
                prim.issue("expected an object");
                continue;
            }
            prim.require("attributes");
            JsonView attributes = prim.object("attributes");
            std::optional<uint64_t> mode = prim.uint("mode");
            if (mode && *mode > 6) prim.issueAt("mode", "invalid mode " + std::to_string(*mode));
            if (mode.value_or(4) == 4 && attributes.has("POSITION")) {
                validatePrimitive(gltf, prim, quantized);
            }
        }
    }
}

}  // namespace

void validateData(const GltfJson& gltf, const GltfDocument& doc) {
    for (size_t i = 0; i < gltf.count("buffers"); ++i) validateBuffer(gltf, doc, i);
    for (size_t i = 0; i < gltf.count("bufferViews"); ++i) validateBufferView(gltf, i);
    for (size_t i = 0; i < gltf.count("accessors"); ++i) validateAccessor(gltf, i);
    bool quantized = false;
    JsonView used = gltf.rootView().silent().array("extensionsUsed");
    for (size_t i = 0; i < used.size(); ++i) {
        std::optional<std::string> name = used.stringAt(i);
        if (name && name->compare("KHR_mesh_quantization") == 0) quantized = true;
    }
    validateMeshes(gltf, quantized);
}

}  // namespace fovea::scene::gltf
