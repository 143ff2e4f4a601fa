// Mesh construction for the built-in scenes: flat triangles and quads oriented by a reference
// point (so a wall's normal faces into the room whatever order the source data lists its
// corners in), and smooth-shaded vertices for procedural shapes.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "core/scene/Scene.h"

namespace fovea::scene {

class MeshBuilder {
public:
    explicit MeshBuilder(TriangleMesh& mesh) : mMesh(mesh) {}

    // One flat-shaded triangle, front face counter-clockwise (normal = (b-a) x (c-a)).
    void triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, uint32_t material);
    // The same triangle, wound so that its normal points towards `towards`.
    void triangleFacing(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                        uint32_t material, const glm::vec3& towards);
    // A quad a-b-c-d (in order around its border) as triangles (a,b,c) and (a,c,d), both facing
    // `towards`.
    void quadFacing(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
                    uint32_t material, const glm::vec3& towards);

    // Smooth shading: add vertices, then triangles that index them (counter-clockwise front).
    uint32_t vertex(const glm::vec3& position, const glm::vec3& normal,
                    const glm::vec2& uv = glm::vec2(0.0f));
    void indexed(uint32_t a, uint32_t b, uint32_t c, uint32_t material);

    TriangleMesh& mesh() { return mMesh; }

private:
    TriangleMesh& mMesh;
};

}  // namespace fovea::scene
