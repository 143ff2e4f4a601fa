// Byte layout of glTF accessors (glTF 2.0 §3.6.2) and overflow-checked arithmetic for the bounds
// checks: counts and offsets come straight from the file, so every product and sum that decides
// whether a read stays inside a buffer is computed with overflow detection.
#pragma once
#include <cstdint>
#include <string_view>

namespace fovea::scene::gltf {

enum ComponentType : uint32_t {
    kByte = 5120,
    kUnsignedByte = 5121,
    kShort = 5122,
    kUnsignedShort = 5123,
    kUnsignedInt = 5125,
    kFloat = 5126,
};

constexpr uint32_t kTargetArrayBuffer = 34962;
constexpr uint32_t kTargetElementArrayBuffer = 34963;

// Bytes per component; 0 for an invalid componentType.
inline uint64_t componentBytes(uint64_t componentType) {
    switch (componentType) {
        case kByte:
        case kUnsignedByte:
            return 1;
        case kShort:
        case kUnsignedShort:
            return 2;
        case kUnsignedInt:
        case kFloat:
            return 4;
        default:
            return 0;
    }
}

// Components per element; 0 for an invalid type.
inline uint64_t typeComponents(std::string_view type) {
    if (type == "SCALAR") return 1;
    if (type == "VEC2") return 2;
    if (type == "VEC3") return 3;
    if (type == "VEC4") return 4;
    if (type == "MAT2") return 4;
    if (type == "MAT3") return 9;
    if (type == "MAT4") return 16;
    return 0;
}

// Bytes per element. Matrix columns start on 4-byte boundaries (§3.6.2.4), so a MAT3 of bytes is
// 12 bytes, not 9.
inline uint64_t elementBytes(std::string_view type, uint64_t componentType) {
    uint64_t component = componentBytes(componentType);
    uint64_t components = typeComponents(type);
    if (component == 0 || components == 0) return 0;
    uint64_t rows = type == "MAT2" ? 2 : type == "MAT3" ? 3 : type == "MAT4" ? 4 : 0;
    if (rows == 0) return component * components;
    uint64_t column = (rows * component + 3) / 4 * 4;
    return column * rows;
}

// Limits that keep a hostile file from asking for unbounded memory: an accessor without buffer
// view (all zeros, or only sparse values) or a node tree instancing a mesh many times costs memory
// without bytes in the file. An accessor with a buffer view is bounded by its bytes, which must
// be in the file (2 GiB at most), so it may be as large as the scene limits allow: one primitive
// can hold a whole 10M- or 60M-triangle scene (issue 28). Documented in docs/scenes.md.
constexpr uint64_t kMaxSceneTriangles = uint64_t(1) << 26;        // 67.1M
constexpr uint64_t kMaxSceneVertices = uint64_t(1) << 27;         // 134.2M
constexpr uint64_t kMaxZeroAccessorElements = uint64_t(1) << 24;  // 16.7M, no buffer view
// The most elements an accessor may have: indices of kMaxSceneTriangles triangles, or
// kMaxSceneVertices vertices; kMaxZeroAccessorElements without a buffer view.
constexpr uint64_t maxAccessorElements(bool hasBufferView, bool indices) {
    if (!hasBufferView) return kMaxZeroAccessorElements;
    return indices ? 3 * kMaxSceneTriangles : kMaxSceneVertices;
}
// Largest |coordinate| of a vertex after its node transform, and largest emission (factor x
// strength). 32-bit floats hold 3.4e38, but bounds extents, BVH surface areas (squared lengths)
// and variance/regression terms (squared radiance) overflow long before: sqrt(3.4e38) = 1.8e19,
// and 1e15 leaves four orders of magnitude for sums over pixels and frames.
constexpr double kMaxSceneCoordinate = 1e15;
constexpr double kMaxEmission = 1e15;

// a * b + c, false on overflow.
inline bool mulAdd(uint64_t a, uint64_t b, uint64_t c, uint64_t& out) {
    uint64_t product = 0;
    if (__builtin_mul_overflow(a, b, &product)) return false;
    return !__builtin_add_overflow(product, c, &out);
}

// Bytes an accessor of `count` elements spans from its first byte: (count-1) * stride + element.
inline bool accessorSpan(uint64_t count, uint64_t stride, uint64_t element, uint64_t& out) {
    if (count == 0) {
        out = 0;
        return true;
    }
    return mulAdd(count - 1, stride, element, out);
}

}  // namespace fovea::scene::gltf
