// Procedural test scenes and a CPU reference ray-triangle test for the BVH / SceneGpu tests
// (the glTF loaders are tested elsewhere; these scenes need no files).
#pragma once
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <random>
#include <utility>

#include "core/scene/Scene.h"

namespace fovea::test {

inline void addTriangle(scene::TriangleMesh& mesh, const glm::vec3& a, const glm::vec3& b,
                        const glm::vec3& c, uint32_t material = 0) {
    const uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    glm::vec3 n = glm::cross(b - a, c - a);
    const float len = glm::length(n);
    n = len > 0.0f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
    for (const glm::vec3& p : {a, b, c}) {
        mesh.positions.push_back(p);
        mesh.normals.push_back(n);
        mesh.uvs.push_back(glm::vec2(p.x, p.y));
    }
    mesh.triangles.push_back(glm::uvec3(base, base + 1, base + 2));
    mesh.materialIds.push_back(material);
}

// Random triangles with centres in [-extent, extent]^3 and edges up to `size` long.
inline scene::TriangleMesh triangleSoup(uint32_t count, uint32_t seed, float extent = 1.0f,
                                        float size = 0.2f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> centre(-extent, extent), offset(-size, size);
    scene::TriangleMesh mesh;
    for (uint32_t i = 0; i < count; ++i) {
        const glm::vec3 c(centre(rng), centre(rng), centre(rng));
        auto corner = [&] { return c + glm::vec3(offset(rng), offset(rng), offset(rng)); };
        const glm::vec3 a = corner(), b = corner(), d = corner();
        addTriangle(mesh, a, b, d);
    }
    return mesh;
}

// A wavy height field over [-1, 1]^2 with shared vertices: (n x n) quads, 2 n^2 triangles.
inline scene::TriangleMesh gridMesh(uint32_t n) {
    scene::TriangleMesh mesh;
    for (uint32_t y = 0; y <= n; ++y)
        for (uint32_t x = 0; x <= n; ++x) {
            const float u = float(x) / n, v = float(y) / n;
            mesh.positions.push_back(glm::vec3(2.0f * u - 1.0f, 2.0f * v - 1.0f,
                                               0.1f * std::sin(9.0f * u) * std::cos(7.0f * v)));
            mesh.normals.push_back(glm::vec3(0.0f, 0.0f, 1.0f));
            mesh.uvs.push_back(glm::vec2(u, v));
        }
    for (uint32_t y = 0; y < n; ++y)
        for (uint32_t x = 0; x < n; ++x) {
            const uint32_t i = y * (n + 1) + x;
            mesh.triangles.push_back(glm::uvec3(i, i + 1, i + n + 2));
            mesh.triangles.push_back(glm::uvec3(i, i + n + 2, i + n + 1));
            mesh.materialIds.push_back(0);
            mesh.materialIds.push_back(0);
        }
    return mesh;
}

// The surface of [-1, 1]^3, each face split into (n x n) quads, outward CCW winding. Rays from
// inside must always hit.
inline scene::TriangleMesh closedBox(uint32_t n) {
    scene::TriangleMesh mesh;
    for (int axis = 0; axis < 3; ++axis)
        for (float side : {-1.0f, 1.0f}) {
            const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
            auto point = [&](uint32_t i, uint32_t j) {
                glm::vec3 p(0.0f);
                p[axis] = side;
                p[ua] = -1.0f + 2.0f * float(i) / n;
                p[va] = -1.0f + 2.0f * float(j) / n;
                return p;
            };
            for (uint32_t j = 0; j < n; ++j)
                for (uint32_t i = 0; i < n; ++i) {
                    glm::vec3 a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1),
                              d = point(i, j + 1);
                    if (side < 0.0f) std::swap(b, d);  // keep the winding outward
                    addTriangle(mesh, a, b, c);
                    addTriangle(mesh, a, c, d);
                }
        }
    return mesh;
}

inline scene::Scene sceneFromMesh(scene::TriangleMesh mesh) {
    scene::Scene s;
    s.source = "test:procedural";
    s.mesh = std::move(mesh);
    s.materials.resize(1);
    for (const auto& p : s.mesh.positions) s.bounds.grow(p);
    return s;
}

// Same arithmetic as bvhIntersectTriangle in shaders/common/bvh.glsl (float Moeller-Trumbore,
// division-free tests, edges inclusive), on v0 and edges computed like SceneGpu does.
inline bool intersectTriangle(const glm::vec3& origin, const glm::vec3& direction,
                              const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                              float tMin, float tMax, float& t, glm::vec2& bary) {
    const glm::vec3 e1 = b - a, e2 = c - a;
    const glm::vec3 p = glm::cross(direction, e2);
    const float det = glm::dot(e1, p);
    const float s = det < 0.0f ? -1.0f : 1.0f;
    const float absDet = std::abs(det);
    const glm::vec3 tv = origin - a;
    const float u = glm::dot(tv, p) * s;
    const float slack = 1e-6f * absDet;  // kBvhEdgeSlack
    if (!(u >= -slack && u <= absDet + slack)) return false;
    const glm::vec3 q = glm::cross(tv, e1);
    const float v = glm::dot(direction, q) * s;
    if (!(v >= -slack && u + v <= absDet + slack)) return false;
    const float tScaled = glm::dot(e2, q) * s;
    if (!(absDet > 0.0f)) return false;
    const float inv = 1.0f / absDet;
    const float tt = tScaled * inv;
    if (!(tt > tMin && tt < tMax)) return false;
    t = tt;
    glm::vec2 w = glm::clamp(glm::vec2(u, v) * inv, 0.0f, 1.0f);
    bary = w.x + w.y > 1.0f ? w / (w.x + w.y) : w;
    return true;
}

struct CpuHit {
    bool hit = false;
    float t = std::numeric_limits<float>::infinity();
    uint32_t triangle = 0;  // mesh index
    glm::vec2 bary{0.0f};
};

inline bool intersectMeshTriangle(const scene::TriangleMesh& mesh, uint32_t tri, const glm::vec3& o,
                                  const glm::vec3& d, float tMin, float tMax, float& t,
                                  glm::vec2& bary) {
    const glm::uvec3 idx = mesh.triangles[tri];
    return intersectTriangle(o, d, mesh.positions[idx.x], mesh.positions[idx.y],
                             mesh.positions[idx.z], tMin, tMax, t, bary);
}

}  // namespace fovea::test
