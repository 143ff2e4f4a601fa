#include "core/scene/gltf/GltfAccessor.h"

#include <algorithm>
#include <cstring>

#include "core/scene/gltf/GltfLayout.h"
#include "core/util/Error.h"

namespace fovea::scene::gltf {

namespace {

// Where the elements of one accessor (or one half of a sparse accessor) live in memory.
struct Elements {
    const uint8_t* base = nullptr;  // nullptr = no buffer view: every element is zero
    uint64_t stride = 0;
};

std::string accessorPointer(size_t accessor) {
    return "/accessors/" + std::to_string(accessor);
}

// Locates `count` elements of `elementBytes` at `byteOffset` in buffer view `viewIndex` and
// proves they lie inside the loaded buffer.
Elements locate(const tinygltf::Model& model, int viewIndex, uint64_t byteOffset, uint64_t count,
                uint64_t elementBytes, bool allowStride, const std::string& file,
                const std::string& pointer) {
    if (viewIndex < 0) return {};
    auto fail = [&](const std::string& message) { return InputError(file, pointer, message); };
    if (size_t(viewIndex) >= model.bufferViews.size()) throw fail("bufferView out of range");
    const tinygltf::BufferView& view = model.bufferViews[size_t(viewIndex)];
    if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) {
        throw fail("buffer out of range");
    }
    const std::vector<unsigned char>& data = model.buffers[size_t(view.buffer)].data;
    uint64_t viewEnd = 0;
    if (!mulAdd(1, view.byteOffset, view.byteLength, viewEnd) || viewEnd > data.size()) {
        throw fail("bufferView " + std::to_string(viewIndex) + " lies outside its buffer");
    }
    uint64_t stride = allowStride && view.byteStride ? view.byteStride : elementBytes;
    uint64_t span = 0, end = 0;
    if (stride < elementBytes || !accessorSpan(count, stride, elementBytes, span) ||
        !mulAdd(1, byteOffset, span, end) || end > view.byteLength) {
        throw fail("data lies outside bufferView " + std::to_string(viewIndex));
    }
    return {data.data() + view.byteOffset + byteOffset, stride};
}

double readComponent(const uint8_t* p, int componentType, bool normalized) {
    switch (componentType) {
        case kByte: {
            int8_t v;
            std::memcpy(&v, p, 1);
            return normalized ? std::max(double(v) / 127.0, -1.0) : double(v);
        }
        case kUnsignedByte: {
            uint8_t v;
            std::memcpy(&v, p, 1);
            return normalized ? double(v) / 255.0 : double(v);
        }
        case kShort: {
            int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(double(v) / 32767.0, -1.0) : double(v);
        }
        case kUnsignedShort: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? double(v) / 65535.0 : double(v);
        }
        case kUnsignedInt: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return double(v);
        }
        case kFloat: {
            float v;
            std::memcpy(&v, p, 4);
            return double(v);
        }
        default:
            return 0.0;
    }
}

uint32_t readIndex(const uint8_t* p, int componentType) {
    if (componentType == kUnsignedByte) return p[0];
    if (componentType == kUnsignedShort) {
        uint16_t v;
        std::memcpy(&v, p, 2);
        return v;
    }
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}

const tinygltf::Accessor& accessorAt(const tinygltf::Model& model, size_t index,
                                     const std::string& file) {
    if (index >= model.accessors.size()) {
        throw InputError(file, accessorPointer(index), "accessor out of range");
    }
    return model.accessors[index];
}

// Calls `apply(slot, elementPointer)` for every sparse substitution, after checking that the
// sparse indices are strictly increasing and inside the accessor (glTF 2.0 §3.6.2.3).
template <typename Apply>
void forSparse(const tinygltf::Model& model, const tinygltf::Accessor& accessor, size_t index,
               uint64_t elementBytes, const std::string& file, Apply apply) {
    if (!accessor.sparse.isSparse) return;
    const auto& sparse = accessor.sparse;
    std::string pointer = accessorPointer(index) + "/sparse";
    if (sparse.count <= 0 || uint64_t(sparse.count) > accessor.count ||
        sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0) {
        throw InputError(file, pointer, "invalid sparse count or offsets");
    }
    uint64_t indexBytes = componentBytes(uint64_t(sparse.indices.componentType));
    if (indexBytes == 0 || sparse.indices.componentType == kByte ||
        sparse.indices.componentType == kShort) {
        throw InputError(file, pointer + "/indices/componentType", "invalid index type");
    }
    uint64_t n = uint64_t(sparse.count);
    Elements indices = locate(model, sparse.indices.bufferView, uint64_t(sparse.indices.byteOffset),
                              n, indexBytes, false, file, pointer + "/indices");
    Elements values = locate(model, sparse.values.bufferView, uint64_t(sparse.values.byteOffset), n,
                             elementBytes, false, file, pointer + "/values");
    if (!indices.base || !values.base) {
        throw InputError(file, pointer, "sparse indices and values need buffer views");
    }
    int64_t previous = -1;
    for (uint64_t i = 0; i < n; ++i) {
        uint32_t slot = readIndex(indices.base + i * indexBytes, sparse.indices.componentType);
        if (int64_t(slot) <= previous || slot >= accessor.count) {
            throw InputError(
                file, pointer + "/indices",
                "sparse index " + std::to_string(slot) + " at position " + std::to_string(i) +
                    (slot >= accessor.count
                         ? " is out of range (count " + std::to_string(accessor.count) + ")"
                         : " is not strictly increasing"));
        }
        previous = slot;
        apply(slot, values.base + i * elementBytes);
    }
}

// Throws at <accessor>/count when the accessor has more elements than maxAccessorElements
// allows, saying why the limit is what it is.
void checkElementCount(const tinygltf::Accessor& accessor, size_t index, bool indices,
                       const std::string& file) {
    const bool hasBufferView = accessor.bufferView >= 0;
    const uint64_t limit = maxAccessorElements(hasBufferView, indices);
    if (accessor.count <= limit) return;
    throw InputError(
        file, accessorPointer(index) + "/count",
        std::to_string(accessor.count) + (indices ? " indices" : " elements") +
            " exceed fovea's limit of " + std::to_string(limit) +
            (hasBufferView ? " (the scene limits: " + std::to_string(kMaxSceneTriangles) +
                                 " triangles, " + std::to_string(kMaxSceneVertices) + " vertices)"
                           : " for an accessor without buffer view (its zeros cost memory but "
                             "no bytes in the file)"));
}

}  // namespace

std::vector<float> readAccessorFloats(const tinygltf::Model& model, size_t index,
                                      uint32_t components, const std::string& file) {
    const tinygltf::Accessor& accessor = accessorAt(model, index, file);
    int typeComponents = tinygltf::GetNumComponentsInType(uint32_t(accessor.type));
    uint64_t component = componentBytes(uint64_t(accessor.componentType));
    if (typeComponents != int(components) || component == 0) {
        throw InputError(file, accessorPointer(index),
                         "expected " + std::to_string(components) + " components per element");
    }
    uint64_t elementBytes = component * components;
    uint64_t count = accessor.count;
    checkElementCount(accessor, index, false, file);
    uint64_t total = count * components;
    std::vector<float> out(size_t(total), 0.0f);
    Elements elements = locate(model, accessor.bufferView, accessor.byteOffset, count, elementBytes,
                               true, file, accessorPointer(index));
    auto decode = [&](uint64_t slot, const uint8_t* p) {
        for (uint32_t c = 0; c < components; ++c) {
            out[size_t(slot * components + c)] = float(
                readComponent(p + c * component, accessor.componentType, accessor.normalized));
        }
    };
    if (elements.base) {
        for (uint64_t i = 0; i < count; ++i) decode(i, elements.base + i * elements.stride);
    }
    forSparse(model, accessor, index, elementBytes, file, decode);
    return out;
}

std::vector<uint32_t> readAccessorIndices(const tinygltf::Model& model, size_t index,
                                          const std::string& file) {
    const tinygltf::Accessor& accessor = accessorAt(model, index, file);
    int type = accessor.componentType;
    if (accessor.type != TINYGLTF_TYPE_SCALAR ||
        (type != kUnsignedByte && type != kUnsignedShort && type != kUnsignedInt)) {
        throw InputError(file, accessorPointer(index), "indices must be unsigned scalars");
    }
    uint64_t bytes = componentBytes(uint64_t(type));
    checkElementCount(accessor, index, true, file);
    std::vector<uint32_t> out(size_t(accessor.count), 0);
    Elements elements = locate(model, accessor.bufferView, accessor.byteOffset, accessor.count,
                               bytes, false, file, accessorPointer(index));
    if (elements.base) {
        for (uint64_t i = 0; i < accessor.count; ++i) {
            out[size_t(i)] = readIndex(elements.base + i * bytes, type);
        }
    }
    forSparse(model, accessor, index, bytes, file,
              [&](uint64_t slot, const uint8_t* p) { out[size_t(slot)] = readIndex(p, type); });
    return out;
}

}  // namespace fovea::scene::gltf
