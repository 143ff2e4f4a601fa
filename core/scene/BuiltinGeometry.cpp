#include "core/scene/BuiltinGeometry.h"

#include <cmath>

namespace fovea::scene {

void MeshBuilder::triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                           uint32_t material) {
    glm::vec3 n = glm::cross(b - a, c - a);
    float length = glm::length(n);
    n = length > 0.0f ? n / length : glm::vec3(0.0f, 1.0f, 0.0f);
    uint32_t first = uint32_t(mMesh.positions.size());
    for (const glm::vec3* p : {&a, &b, &c}) {
        mMesh.positions.push_back(*p);
        mMesh.normals.push_back(n);
        mMesh.uvs.emplace_back(0.0f);
    }
    mMesh.triangles.emplace_back(first, first + 1, first + 2);
    mMesh.materialIds.push_back(material);
}

void MeshBuilder::triangleFacing(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                                 uint32_t material, const glm::vec3& towards) {
    glm::vec3 n = glm::cross(b - a, c - a);
    glm::vec3 centroid = (a + b + c) / 3.0f;
    if (glm::dot(n, towards - centroid) >= 0.0f) {
        triangle(a, b, c, material);
    } else {
        triangle(a, c, b, material);
    }
}

void MeshBuilder::quadFacing(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                             const glm::vec3& d, uint32_t material, const glm::vec3& towards) {
    triangleFacing(a, b, c, material, towards);
    triangleFacing(a, c, d, material, towards);
}

uint32_t MeshBuilder::vertex(const glm::vec3& position, const glm::vec3& normal,
                             const glm::vec2& uv) {
    uint32_t index = uint32_t(mMesh.positions.size());
    mMesh.positions.push_back(position);
    float length = glm::length(normal);
    mMesh.normals.push_back(length > 0.0f ? normal / length : glm::vec3(0.0f, 1.0f, 0.0f));
    mMesh.uvs.push_back(uv);
    return index;
}

void MeshBuilder::indexed(uint32_t a, uint32_t b, uint32_t c, uint32_t material) {
    mMesh.triangles.emplace_back(a, b, c);
    mMesh.materialIds.push_back(material);
}

}  // namespace fovea::scene
