#include "core/scene/GltfMesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <type_traits>

#include "core/scene/GltfAccessor.h"
#include "core/scene/GltfLayout.h"
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

}  // namespace

void appendPrimitive(const tinygltf::Model& model, size_t meshIndex, size_t primIndex,
                     int64_t indexAccessor, const glm::dmat4& world, uint32_t materialId,
                     bool normalMapped, const std::string& file, TriangleMesh& out,
                     std::set<std::string>& warnings) {
    const tinygltf::Primitive& prim = model.meshes.at(meshIndex).primitives.at(primIndex);
    std::string pointer =
        "/meshes/" + std::to_string(meshIndex) + "/primitives/" + std::to_string(primIndex);
    int positionAccessor = attribute(prim, "POSITION");
    std::vector<float> raw = readAccessorFloats(model, size_t(positionAccessor), 3, file);
    size_t vertexCount = raw.size() / 3;
    for (size_t i = 0; i < raw.size(); ++i) {
        if (!std::isfinite(raw[i])) {
            throw InputError(file, "/accessors/" + std::to_string(positionAccessor),
                             "POSITION of vertex " + std::to_string(i / 3) + " is not finite");
        }
    }
    std::vector<float> rawNormals, rawUvs;
    if (int a = attribute(prim, "NORMAL"); a >= 0) {
        rawNormals = readAccessorFloats(model, size_t(a), 3, file);
    }
    if (int a = attribute(prim, "TEXCOORD_0"); a >= 0) {
        rawUvs = readAccessorFloats(model, size_t(a), 2, file);
        for (size_t i = 0; i < rawUvs.size(); ++i) {
            if (!std::isfinite(rawUvs[i])) {
                throw InputError(
                    file, "/accessors/" + std::to_string(a),
                    "TEXCOORD_0 of vertex " + std::to_string(i / 2) + " is not finite");
            }
        }
    }
    // COLOR_0 (§3.7.2.1) multiplies the base colour; RGB gets alpha 1. Float values must lie in
    // [0, 1] (the validator's ACCESSOR_NON_CLAMPED is an error too): outside, or NaN, is an error.
    std::vector<glm::vec4> colors;
    if (int a = attribute(prim, "COLOR_0"); a >= 0) {
        const uint32_t components =
            model.accessors.at(size_t(a)).type == TINYGLTF_TYPE_VEC3 ? 3u : 4u;
        const std::vector<float> rawColors = readAccessorFloats(model, size_t(a), components, file);
        colors.resize(rawColors.size() / components, glm::vec4(1.0f));
        for (size_t i = 0; i < rawColors.size(); ++i) {
            const float v = rawColors[i];
            if (!(v >= 0.0f && v <= 1.0f)) {
                char value[32];
                std::snprintf(value, sizeof value, "%g", double(v));
                throw InputError(file, "/accessors/" + std::to_string(a),
                                 "COLOR_0 of vertex " + std::to_string(i / components) + " is " +
                                     value + ", outside [0, 1] (" + pointer + ")");
            }
            colors[i / components][int(i % components)] = v;
        }
    }
    // TANGENT (§3.7.2.1: VEC4 float, xyz unit, w = +-1) only where a normal texture uses it.
    std::vector<glm::vec4> rawTangents;
    int tangentAccessor = normalMapped ? attribute(prim, "TANGENT") : -1;
    if (tangentAccessor >= 0) rawTangents = readTangents(model, size_t(tangentAccessor), file);
    if ((!rawTangents.empty() && rawTangents.size() != vertexCount) ||
        (!rawNormals.empty() && rawNormals.size() != raw.size()) ||
        (!rawUvs.empty() && rawUvs.size() / 2 != vertexCount) ||
        (!colors.empty() && colors.size() != vertexCount)) {
        throw InputError(file, pointer + "/attributes", "attribute counts differ");
    }
    std::vector<uint32_t> indices = readIndices(model, indexAccessor, vertexCount, file, pointer);
    size_t triangles = indices.size() / 3;
    if (indices.size() % 3 != 0) {
        warnings.insert(pointer + ": " + std::to_string(indices.size() % 3) +
                        " trailing vertices do not form a triangle and are ignored");
    }

    glm::dmat3 linear(world);
    double det = glm::determinant(linear);
    bool flip = det < 0.0;
    glm::dmat3 normalMatrix = glm::transpose(glm::inverse(linear));
    std::vector<glm::vec3> positions(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) {
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
            throw InputError(file, "/accessors/" + std::to_string(positionAccessor),
                             "POSITION of vertex " + std::to_string(i) + " is at " + value +
                                 " after the node transform (" + pointer +
                                 "): coordinates beyond 1e15 overflow the 32-bit float bounds, "
                                 "BVH and ray distances");
        }
    }
    auto uvAt = [&](size_t i) {
        return rawUvs.empty() ? glm::vec2(0.0f) : glm::vec2(rawUvs[2 * i], rawUvs[2 * i + 1]);
    };
    uint64_t base = out.positions.size();
    uint64_t added = rawNormals.empty() ? uint64_t(triangles) * 3 : vertexCount;
    if (base + added > kMaxSceneVertices || out.triangles.size() + triangles > kMaxSceneTriangles) {
        throw InputError(file, pointer,
                         "the flattened scene exceeds fovea's limits of " +
                             std::to_string(kMaxSceneTriangles) + " triangles and " +
                             std::to_string(kMaxSceneVertices) + " vertices");
    }
    out.triangles.reserve(out.triangles.size() + triangles);
    out.materialIds.insert(out.materialIds.end(), triangles, materialId);
    // Colours stay empty until a primitive has some; then every vertex gets one (white before).
    if (!colors.empty() && out.colors.empty())
        out.colors.assign(out.positions.size(), glm::vec4(1.0f));
    const bool withColors = !colors.empty() || !out.colors.empty();
    auto colorAt = [&](size_t i) { return colors.empty() ? glm::vec4(1.0f) : colors[i]; };
    // Tangents likewise: empty until a normal-mapped primitive comes; (0,0,0,1) elsewhere.
    const bool withTangents = normalMapped || !out.tangents.empty();
    if (normalMapped && out.tangents.empty())
        out.tangents.assign(out.positions.size(), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    const size_t firstVertex = out.positions.size(), firstTriangle = out.triangles.size();
    // Called on every return (tangents are kept only once a normal-mapped primitive came).
    const auto finishTangents = [&](const std::vector<uint32_t>& sourceVertex) {
        if (withTangents)
            appendTangents(out, firstVertex, firstTriangle, normalMapped, rawTangents, sourceVertex,
                           linear, flip);
    };

    if (rawNormals.empty()) {
        // Flat normals need a vertex per corner: corners of different faces differ in normal.
        std::vector<uint32_t> sourceVertex;  // the primitive's vertex of each corner
        for (size_t t = 0; t < triangles; ++t) {
            uint32_t a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
            if (flip) std::swap(b, c);
            glm::vec3 n = faceNormal(positions[a], positions[b], positions[c]);
            uint32_t first = uint32_t(out.positions.size());
            for (uint32_t v : {a, b, c}) {
                out.positions.push_back(positions[v]);
                out.normals.push_back(n);
                out.uvs.push_back(uvAt(v));
                if (withColors) out.colors.push_back(colorAt(v));
                sourceVertex.push_back(v);
            }
            out.triangles.emplace_back(first, first + 1, first + 2);
        }
        finishTangents(sourceVertex);
        return;
    }
    std::vector<glm::vec3> normals(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) {
        glm::dvec3 n(rawNormals[3 * i], rawNormals[3 * i + 1], rawNormals[3 * i + 2]);
        normals[i] = glm::vec3(normalMatrix * n);
    }
    if (size_t fixed = repairNormals(normals, positions, indices, triangles, flip)) {
        warnings.insert(pointer + ": " + std::to_string(fixed) +
                        " zero or non-finite normals replaced by face normals");
    }
    for (size_t i = 0; i < vertexCount; ++i) {
        out.positions.push_back(positions[i]);
        out.normals.push_back(normals[i]);
        out.uvs.push_back(uvAt(i));
        if (withColors) out.colors.push_back(colorAt(i));
    }
    for (size_t t = 0; t < triangles; ++t) {
        uint32_t a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
        if (flip) std::swap(b, c);
        out.triangles.emplace_back(uint32_t(base) + a, uint32_t(base) + b, uint32_t(base) + c);
    }
    finishTangents({});
}

}  // namespace fovea::scene::gltf
