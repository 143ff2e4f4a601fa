#include "core/scene/gltf/GltfMesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>

#include "core/scene/gltf/GltfAccessor.h"
#include "core/scene/gltf/GltfLayout.h"
#include "core/scene/Tangents.h"
#include "core/util/Error.h"

namespace fovea::scene::gltf {

namespace {

// A degenerate triangle has no direction; any unit vector will do since it covers no area and
// is never hit. "Up" keeps the data finite.
const glm::vec3 kFallbackNormal(0.0f, 1.0f, 0.0f);

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::vec3 faceNormal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    glm::vec3 n = glm::cross(b - a, c - a);
    float length = glm::length(n);
    return length > 0.0f && std::isfinite(length) ? n / length : kFallbackNormal;
}

int attribute(const tinygltf::Primitive& prim, const char* name) {
    auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
}

uint32_t restartValue(int componentType) {
    return componentType == kUnsignedByte    ? 0xFFu
           : componentType == kUnsignedShort ? 0xFFFFu
                                             : 0xFFFFFFFFu;
}

std::vector<uint32_t> readIndices(const tinygltf::Model& model, int64_t accessor,
                                  size_t vertexCount, const std::string& file,
                                  const std::string& pointer) {
    if (accessor < 0) {
        std::vector<uint32_t> sequence(vertexCount);
        for (size_t i = 0; i < vertexCount; ++i) sequence[i] = uint32_t(i);
        return sequence;
    }
    std::vector<uint32_t> indices = readAccessorIndices(model, size_t(accessor), file);
    uint32_t restart = restartValue(model.accessors[size_t(accessor)].componentType);
    for (size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= vertexCount || indices[i] == restart) {
            throw InputError(
                file, pointer + "/indices",
                "index value " + std::to_string(indices[i]) + " at position " + std::to_string(i) +
                    (indices[i] >= vertexCount ? " is out of range: POSITION has " +
                                                     std::to_string(vertexCount) + " vertices"
                                               : " is the primitive restart value (not allowed)"));
        }
    }
    return indices;
}

// Replaces unusable normals by the area-weighted sum of the adjacent triangles' normals.
size_t repairNormals(std::vector<glm::vec3>& normals, const std::vector<glm::vec3>& positions,
                     const std::vector<uint32_t>& indices, size_t triangles, bool flip) {
    std::vector<char> bad(normals.size(), 0);
    size_t badCount = 0;
    for (size_t i = 0; i < normals.size(); ++i) {
        float length = glm::length(normals[i]);
        if (!(std::isfinite(length) && length > 1e-20f)) {
            bad[i] = 1;
            ++badCount;
        } else {
            normals[i] /= length;
        }
    }
    if (badCount == 0) return 0;
    std::vector<glm::vec3> sums(normals.size(), glm::vec3(0.0f));
    for (size_t t = 0; t < triangles; ++t) {
        uint32_t a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
        if (flip) std::swap(b, c);
        // The cross product's length is twice the area: the weighting comes for free.
        glm::vec3 n = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
        if (!finite(n)) continue;
        for (uint32_t v : {a, b, c}) sums[v] += n;
    }
    for (size_t i = 0; i < normals.size(); ++i) {
        if (!bad[i]) continue;
        float length = glm::length(sums[i]);
        normals[i] = length > 0.0f && std::isfinite(length) ? sums[i] / length : kFallbackNormal;
    }
    return badCount;
}

// TANGENT values (§3.7.2.1: VEC4 float): xyz finite and not zero, w +1 or -1. InputError naming
// the accessor and the vertex otherwise (the validator checks the format).
std::vector<glm::vec4> readTangents(const tinygltf::Model& model, size_t accessor,
                                    const std::string& file) {
    const std::vector<float> raw = readAccessorFloats(model, accessor, 4, file);
    std::vector<glm::vec4> out(raw.size() / 4);
    for (size_t i = 0; i < out.size(); ++i) {
        out[i] = glm::vec4(raw[4 * i], raw[4 * i + 1], raw[4 * i + 2], raw[4 * i + 3]);
        const float length = glm::length(glm::vec3(out[i]));
        if (!(length > 1e-6f) || !std::isfinite(length) ||
            std::abs(std::abs(out[i].w) - 1.0f) > 1e-3f) {
            char value[96];
            std::snprintf(value, sizeof value, "(%g, %g, %g, %g)", double(out[i].x),
                          double(out[i].y), double(out[i].z), double(out[i].w));
            throw InputError(file, "/accessors/" + std::to_string(accessor),
                             "TANGENT of vertex " + std::to_string(i) + " is " + value +
                                 ": xyz must be a finite non-zero vector and w +1 or -1");
        }
    }
    return out;
}

// The tangents of one primitive's vertices, out.positions[firstVertex..]: from TANGENT
// (`fromFile`, indexed by `sourceVertex` when corners were split for flat normals; the model
// matrix applied to xyz, w flipped by a mirroring node, §3.7.4), else generated from the UVs; the
// placeholder (0,0,0,1) when the primitive is not normal-mapped.
void appendTangents(TriangleMesh& out, size_t firstVertex, size_t firstTriangle, bool normalMapped,
                    const std::vector<glm::vec4>& fromFile,
                    const std::vector<uint32_t>& sourceVertex, const glm::dmat3& linear,
                    bool flip) {
    if (!normalMapped) {
        out.tangents.resize(out.positions.size(), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        return;
    }
    if (!fromFile.empty()) {
        for (size_t i = firstVertex; i < out.positions.size(); ++i) {
            const size_t k = i - firstVertex;
            const glm::vec4 t = fromFile[sourceVertex.empty() ? k : sourceVertex[k]];
            glm::vec3 xyz = glm::vec3(linear * glm::dvec3(t));
            const glm::vec3 n = out.normals[i];
            xyz -= n * glm::dot(n, xyz);  // back to the tangent plane after a shear
            const float length = glm::length(xyz);
            out.tangents.push_back(
                length > 0.0f && std::isfinite(length)
                    ? glm::vec4(xyz / length, (t.w < 0.0f) != flip ? -1.0f : 1.0f)
                    : glm::vec4(perpendicularTo(n), 1.0f));
        }
        return;
    }
    std::vector<glm::uvec3> local;
    local.reserve(out.triangles.size() - firstTriangle);
    for (size_t t = firstTriangle; t < out.triangles.size(); ++t)
        local.push_back(out.triangles[t] - glm::uvec3(uint32_t(firstVertex)));
    const auto tail = [&](const auto& v) {
        using T = typename std::decay_t<decltype(v)>::value_type;
        return std::vector<T>(v.begin() + ptrdiff_t(firstVertex), v.end());
    };
    const std::vector<glm::vec4> generated =
        generateTangents(tail(out.positions), tail(out.normals), tail(out.uvs), local);
    out.tangents.insert(out.tangents.end(), generated.begin(), generated.end());
}

// The primitive's vertex attributes as the file stores them (object space), checked: finite
// positions and UVs, colours in [0, 1], valid tangents, one value a vertex in every attribute.
struct PrimitiveAttributes {
    int positionAccessor = -1;
    std::vector<float> positions;     // xyz a vertex
    std::vector<float> normals;       // xyz a vertex; empty when the file has none
    std::vector<float> uvs;           // uv a vertex; empty without TEXCOORD_0
    std::vector<glm::vec4> colors;    // empty without COLOR_0
    std::vector<glm::vec4> tangents;  // empty unless normal-mapped and the file has TANGENT

    size_t vertexCount() const { return positions.size() / 3; }
    glm::vec2 uvAt(size_t i) const {
        return uvs.empty() ? glm::vec2(0.0f) : glm::vec2(uvs[2 * i], uvs[2 * i + 1]);
    }
    glm::vec4 colorAt(size_t i) const { return colors.empty() ? glm::vec4(1.0f) : colors[i]; }
};

std::vector<float> readPositions(const tinygltf::Model& model, int accessor,
                                 const std::string& file) {
    std::vector<float> raw = readAccessorFloats(model, size_t(accessor), 3, file);
    for (size_t i = 0; i < raw.size(); ++i) {
        if (!std::isfinite(raw[i])) {
            throw InputError(file, "/accessors/" + std::to_string(accessor),
                             "POSITION of vertex " + std::to_string(i / 3) + " is not finite");
        }
    }
    return raw;
}

std::vector<float> readUvs(const tinygltf::Model& model, int accessor, const std::string& file) {
    std::vector<float> rawUvs = readAccessorFloats(model, size_t(accessor), 2, file);
    for (size_t i = 0; i < rawUvs.size(); ++i) {
        if (!std::isfinite(rawUvs[i])) {
            throw InputError(file, "/accessors/" + std::to_string(accessor),
                             "TEXCOORD_0 of vertex " + std::to_string(i / 2) + " is not finite");
        }
    }
    return rawUvs;
}

// COLOR_0 (§3.7.2.1) multiplies the base colour; RGB gets alpha 1. Float values must lie in
// [0, 1] (the validator's ACCESSOR_NON_CLAMPED is an error too): outside, or NaN, is an error.
std::vector<glm::vec4> readColors(const tinygltf::Model& model, int accessor,
                                  const std::string& file, const std::string& pointer) {
    const uint32_t components =
        model.accessors.at(size_t(accessor)).type == TINYGLTF_TYPE_VEC3 ? 3u : 4u;
    const std::vector<float> rawColors =
        readAccessorFloats(model, size_t(accessor), components, file);
    std::vector<glm::vec4> colors(rawColors.size() / components, glm::vec4(1.0f));
    for (size_t i = 0; i < rawColors.size(); ++i) {
        const float v = rawColors[i];
        if (!(v >= 0.0f && v <= 1.0f)) {
            char value[32];
            std::snprintf(value, sizeof value, "%g", double(v));
            throw InputError(file, "/accessors/" + std::to_string(accessor),
                             "COLOR_0 of vertex " + std::to_string(i / components) + " is " +
                                 value + ", outside [0, 1] (" + pointer + ")");
        }
        colors[i / components][int(i % components)] = v;
    }
    return colors;
}

PrimitiveAttributes readAttributes(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                   bool normalMapped, const std::string& file,
                                   const std::string& pointer) {
    PrimitiveAttributes attributes;
    attributes.positionAccessor = attribute(prim, "POSITION");
    attributes.positions = readPositions(model, attributes.positionAccessor, file);
    if (int a = attribute(prim, "NORMAL"); a >= 0) {
        attributes.normals = readAccessorFloats(model, size_t(a), 3, file);
    }
    if (int a = attribute(prim, "TEXCOORD_0"); a >= 0) attributes.uvs = readUvs(model, a, file);
    if (int a = attribute(prim, "COLOR_0"); a >= 0) {
        attributes.colors = readColors(model, a, file, pointer);
    }
    // TANGENT (§3.7.2.1: VEC4 float, xyz unit, w = +-1) only where a normal texture uses it.
    int tangentAccessor = normalMapped ? attribute(prim, "TANGENT") : -1;
    if (tangentAccessor >= 0) {
        attributes.tangents = readTangents(model, size_t(tangentAccessor), file);
    }
    const size_t vertexCount = attributes.vertexCount();
    if ((!attributes.tangents.empty() && attributes.tangents.size() != vertexCount) ||
        (!attributes.normals.empty() && attributes.normals.size() != attributes.positions.size()) ||
        (!attributes.uvs.empty() && attributes.uvs.size() / 2 != vertexCount) ||
        (!attributes.colors.empty() && attributes.colors.size() != vertexCount)) {
        throw InputError(file, pointer + "/attributes", "attribute counts differ");
    }
    return attributes;
}

// The positions placed by the node's world matrix, each checked to stay usable in 32-bit floats.
std::vector<glm::vec3> transformPositions(const PrimitiveAttributes& attributes,
                                          const glm::dmat4& world, const std::string& file,
                                          const std::string& pointer) {
    const std::vector<float>& raw = attributes.positions;
    std::vector<glm::vec3> positions(attributes.vertexCount());
    for (size_t i = 0; i < positions.size(); ++i) {
        glm::dvec4 p = world * glm::dvec4(raw[3 * i], raw[3 * i + 1], raw[3 * i + 2], 1.0);
        positions[i] = glm::vec3(p);
        if (!finite(positions[i])) {
            throw InputError(
                file, pointer,
                "vertex " + std::to_string(i) + " is not finite after the node transform");
        }
        // A finite vertex at 3e38 still overflows the scene bounds (extent 6e38), BVH areas and
        // ray distances in 32-bit floats: the image came out black with exit 0.
        const double largest = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
        if (largest > kMaxSceneCoordinate) {
            char value[32];
            std::snprintf(value, sizeof value, "%g", largest);
            throw InputError(file, "/accessors/" + std::to_string(attributes.positionAccessor),
                             "POSITION of vertex " + std::to_string(i) + " is at " + value +
                                 " after the node transform (" + pointer +
                                 "): coordinates beyond 1e15 overflow the 32-bit float bounds, "
                                 "BVH and ray distances");
        }
    }
    return positions;
}

void checkSceneLimits(const TriangleMesh& out, uint64_t addedVertices, size_t addedTriangles,
                      const std::string& file, const std::string& pointer) {
    const uint64_t base = out.positions.size();
    if (base + addedVertices > kMaxSceneVertices ||
        out.triangles.size() + addedTriangles > kMaxSceneTriangles) {
        throw InputError(file, pointer,
                         "the flattened scene exceeds fovea's limits of " +
                             std::to_string(kMaxSceneTriangles) + " triangles and " +
                             std::to_string(kMaxSceneVertices) + " vertices");
    }
}

// Which of the mesh's optional per-vertex streams this primitive appends to.
struct OptionalStreams {
    bool colors = false;
    bool tangents = false;
};

// Makes room for the primitive's triangles, appends their material ids, and starts the optional
// streams this primitive is the first to need, filled for the vertices already in the mesh.
OptionalStreams startPrimitive(TriangleMesh& out, size_t triangles, uint32_t materialId,
                               bool hasColors, bool normalMapped) {
    out.triangles.reserve(out.triangles.size() + triangles);
    out.materialIds.insert(out.materialIds.end(), triangles, materialId);
    OptionalStreams streams;
    // Colours stay empty until a primitive has some; then every vertex gets one (white before).
    if (hasColors && out.colors.empty()) out.colors.assign(out.positions.size(), glm::vec4(1.0f));
    streams.colors = hasColors || !out.colors.empty();
    // Tangents likewise: empty until a normal-mapped primitive comes; (0,0,0,1) elsewhere.
    streams.tangents = normalMapped || !out.tangents.empty();
    if (normalMapped && out.tangents.empty())
        out.tangents.assign(out.positions.size(), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    return streams;
}

// One output vertex: `position` and `normal` in world space, UV and colour from the primitive's
// vertex `source`.
void appendVertex(TriangleMesh& out, const glm::vec3& position, const glm::vec3& normal,
                  const PrimitiveAttributes& attributes, size_t source, bool withColors) {
    out.positions.push_back(position);
    out.normals.push_back(normal);
    out.uvs.push_back(attributes.uvAt(source));
    if (withColors) out.colors.push_back(attributes.colorAt(source));
}

// Flat normals need a vertex per corner: corners of different faces differ in normal. Returns
// the primitive's vertex of each corner.
std::vector<uint32_t> appendFlatShaded(TriangleMesh& out, const PrimitiveAttributes& attributes,
                                       const std::vector<glm::vec3>& positions,
                                       const std::vector<uint32_t>& indices, size_t triangles,
                                       bool flip, bool withColors) {
    std::vector<uint32_t> sourceVertex;
    for (size_t t = 0; t < triangles; ++t) {
        uint32_t a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
        if (flip) std::swap(b, c);
        glm::vec3 n = faceNormal(positions[a], positions[b], positions[c]);
        uint32_t first = uint32_t(out.positions.size());
        for (uint32_t v : {a, b, c}) {
            appendVertex(out, positions[v], n, attributes, v, withColors);
            sourceVertex.push_back(v);
        }
        out.triangles.emplace_back(first, first + 1, first + 2);
    }
    return sourceVertex;
}

// The file's normals by the inverse transpose of the node's matrix, unusable ones repaired.
std::vector<glm::vec3> transformNormals(const PrimitiveAttributes& attributes,
                                        const glm::dmat3& linear,
                                        const std::vector<glm::vec3>& positions,
                                        const std::vector<uint32_t>& indices, size_t triangles,
                                        bool flip, const std::string& pointer,
                                        std::set<std::string>& warnings) {
    const std::vector<float>& rawNormals = attributes.normals;
    glm::dmat3 normalMatrix = glm::transpose(glm::inverse(linear));
    std::vector<glm::vec3> normals(attributes.vertexCount());
    for (size_t i = 0; i < normals.size(); ++i) {
        glm::dvec3 n(rawNormals[3 * i], rawNormals[3 * i + 1], rawNormals[3 * i + 2]);
        normals[i] = glm::vec3(normalMatrix * n);
    }
    if (size_t fixed = repairNormals(normals, positions, indices, triangles, flip)) {
        warnings.insert(pointer + ": " + std::to_string(fixed) +
                        " zero or non-finite normals replaced by face normals");
    }
    return normals;
}

// The file's normals keep the primitive's vertices shared: one output vertex each.
void appendSmoothShaded(TriangleMesh& out, const PrimitiveAttributes& attributes,
                        const std::vector<glm::vec3>& positions,
                        const std::vector<glm::vec3>& normals, const std::vector<uint32_t>& indices,
                        size_t triangles, bool flip, bool withColors) {
    const uint32_t base = uint32_t(out.positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
        appendVertex(out, positions[i], normals[i], attributes, i, withColors);
    }
    for (size_t t = 0; t < triangles; ++t) {
        uint32_t a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
        if (flip) std::swap(b, c);
        out.triangles.emplace_back(base + a, base + b, base + c);
    }
}

}  // namespace

void appendPrimitive(const tinygltf::Model& model, size_t meshIndex, size_t primIndex,
                     int64_t indexAccessor, const glm::dmat4& world, uint32_t materialId,
                     bool normalMapped, const std::string& file, TriangleMesh& out,
                     std::set<std::string>& warnings) {
    const tinygltf::Primitive& prim = model.meshes.at(meshIndex).primitives.at(primIndex);
    const std::string pointer =
        "/meshes/" + std::to_string(meshIndex) + "/primitives/" + std::to_string(primIndex);
    const PrimitiveAttributes attributes = readAttributes(model, prim, normalMapped, file, pointer);
    const size_t vertexCount = attributes.vertexCount();
    const std::vector<uint32_t> indices =
        readIndices(model, indexAccessor, vertexCount, file, pointer);
    const size_t triangles = indices.size() / 3;
    if (indices.size() % 3 != 0) {
        warnings.insert(pointer + ": " + std::to_string(indices.size() % 3) +
                        " trailing vertices do not form a triangle and are ignored");
    }

    const glm::dmat3 linear(world);
    const bool flip = glm::determinant(linear) < 0.0;
    const std::vector<glm::vec3> positions = transformPositions(attributes, world, file, pointer);
    const bool flatShaded = attributes.normals.empty();
    checkSceneLimits(out, flatShaded ? uint64_t(triangles) * 3 : vertexCount, triangles, file,
                     pointer);
    const OptionalStreams streams =
        startPrimitive(out, triangles, materialId, !attributes.colors.empty(), normalMapped);
    const size_t firstVertex = out.positions.size(), firstTriangle = out.triangles.size();

    std::vector<uint32_t> sourceVertex;  // the primitive's vertex of each corner; empty: shared
    if (flatShaded) {
        sourceVertex =
            appendFlatShaded(out, attributes, positions, indices, triangles, flip, streams.colors);
    } else {
        const std::vector<glm::vec3> normals = transformNormals(
            attributes, linear, positions, indices, triangles, flip, pointer, warnings);
        appendSmoothShaded(out, attributes, positions, normals, indices, triangles, flip,
                           streams.colors);
    }
    // Tangents are kept only once a normal-mapped primitive came.
    if (streams.tangents)
        appendTangents(out, firstVertex, firstTriangle, normalMapped, attributes.tangents,
                       sourceVertex, linear, flip);
}

}  // namespace fovea::scene::gltf
