// Turns one rendered glTF primitive, placed by one node, into world-space triangles: positions by
// the node's world matrix, normals by its inverse transpose (renormalised), winding reversed when
// the matrix mirrors (glTF 2.0 §3.7.4), flat normals generated when the file has none (§3.7.2.1),
// zero or non-finite normals replaced by the area-weighted normal of the adjacent triangles.
// Checked while reading: finite positions and UVs, index values below the vertex count and not
// the primitive-restart value.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <set>
#include <string>

#include "core/scene/Scene.h"
#include "core/scene/gltf/TinyGltf.h"

namespace fovea::scene::gltf {

// `indices`: the primitive's indices accessor (-1 = none), taken from the checked JSON rather
// than from tinygltf (see GltfTiny.cpp). `warnings` is a set because a primitive drawn by several
// nodes reports its problems once. `normalMapped`: the material has a normal texture, so the
// primitive needs tangents (its TANGENT attribute, else generated: core/scene/Tangents.h).
void appendPrimitive(const tinygltf::Model& model, size_t mesh, size_t primitive, int64_t indices,
                     const glm::dmat4& world, uint32_t materialId, bool normalMapped,
                     const std::string& file, TriangleMesh& out, std::set<std::string>& warnings);

}  // namespace fovea::scene::gltf
