// Tangent frames for normal textures when a glTF primitive has no TANGENT attribute (glTF 2.0
// §3.7.2.1 asks for MikkTSpace-compatible tangents when TANGENT is absent).
//
// fovea's generator follows Lengyel (2001, "Computing Tangent Space Basis Vectors for an
// Arbitrary Mesh"): per triangle the directions of increasing u (tangent) and v (bitangent) from
// its UV gradients, summed per vertex weighted by the triangle's UV area (|det|), then Gram-Schmidt
// orthonormalized against the vertex normal; w = the sign of the bitangent against cross(N, T).
// Where it differs from MikkTSpace: MikkTSpace weights by the corner angle, splits
// vertices whose neighbouring triangles disagree in handedness (mirrored UVs) and treats
// degenerate UV triangles by averaging neighbours; here a shared vertex keeps one averaged frame,
// and triangles whose UVs have no area add nothing (a vertex with no usable triangle gets a
// tangent perpendicular to its normal). On meshes without UV seams across mirrored halves the two
// agree up to the weighting.
#pragma once
#include <glm/glm.hpp>
#include <vector>

namespace fovea::scene {

// One tangent per vertex: xyz unit and perpendicular to the (unit) normal, w = +1 or -1.
// `triangles` index `positions`, `normals` and `uvs` (same sizes).
std::vector<glm::vec4> generateTangents(const std::vector<glm::vec3>& positions,
                                        const std::vector<glm::vec3>& normals,
                                        const std::vector<glm::vec2>& uvs,
                                        const std::vector<glm::uvec3>& triangles);

// Any unit vector perpendicular to unit `n` (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited").
glm::vec3 perpendicularTo(const glm::vec3& n);

}  // namespace fovea::scene
