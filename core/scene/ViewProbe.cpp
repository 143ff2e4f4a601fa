#include "core/scene/ViewProbe.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fovea::scene {

namespace {

struct Hit {
    float t = std::numeric_limits<float>::infinity();
    uint32_t triangle = 0;
    bool found = false;
};

// Slab test; `invDir` components may be +-inf (axis-parallel rays), and a NaN from 0 * inf is
// dropped by std::min/std::max ordering below (the comparison with NaN keeps the other value).
bool hitsBox(const BvhNode& node, const glm::vec3& origin, const glm::vec3& invDir, float tMax) {
    float t0 = 0.0f, t1 = tMax;
    for (int a = 0; a < 3; ++a) {
        float near = (node.boundsMin[a] - origin[a]) * invDir[a];
        float far = (node.boundsMax[a] - origin[a]) * invDir[a];
        if (near > far) std::swap(near, far);
        t0 = near > t0 ? near : t0;
        t1 = far < t1 ? far : t1;
        if (t0 > t1) return false;
    }
    return true;
}

// Möller–Trumbore; `det` near 0 (ray parallel to the triangle, or a degenerate one) is no hit.
bool hitsTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& o,
                  const glm::vec3& d, float& t) {
    const glm::vec3 e1 = b - a, e2 = c - a;
    const glm::vec3 p = glm::cross(d, e2);
    const float det = glm::dot(e1, p);
    if (!(std::fabs(det) > 1e-20f)) return false;
    const float inv = 1.0f / det;
    const glm::vec3 s = o - a;
    const float u = glm::dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) return false;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(d, q) * inv;
    if (v < 0.0f || u + v > 1.0f) return false;
    t = glm::dot(e2, q) * inv;
    return t > 0.0f && std::isfinite(t);
}

Hit closestHit(const Scene& scene, const Bvh& bvh, const glm::vec3& o, const glm::vec3& d) {
    Hit hit;
    const glm::vec3 invDir(1.0f / d.x, 1.0f / d.y, 1.0f / d.z);  // inf for a zero component
    const auto& nodes = bvh.nodes();
    const auto& order = bvh.triangleOrder();
    const auto& mesh = scene.mesh;
    uint32_t stack[Bvh::kMaxDepth + 2];
    uint32_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const uint32_t index = stack[--top];
        const BvhNode& node = nodes[index];
        if (!hitsBox(node, o, invDir, hit.t)) continue;
        if (node.isLeaf()) {
            for (uint32_t k = node.index; k < node.index + node.count && k < order.size(); ++k) {
                const glm::uvec3 tri = mesh.triangles[order[k]];
                float t = 0.0f;
                if (hitsTriangle(mesh.positions[tri.x], mesh.positions[tri.y],
                                 mesh.positions[tri.z], o, d, t) &&
                    t < hit.t) {
                    hit = {t, order[k], true};
                }
            }
        } else if (top + 2 <= Bvh::kMaxDepth + 2) {  // the build caps the depth (Bvh.h)
            stack[top++] = node.index;               // right child
            stack[top++] = index + 1;                // left child, depth first
        }
    }
    return hit;
}

}  // namespace

ViewProbe probeView(const Scene& scene, const Bvh& bvh, const FrameCamera& camera, uint32_t gridX,
                    uint32_t gridY) {
    ViewProbe probe;
    probe.gridX = gridX;
    probe.gridY = gridY;
    const float width = float(std::max(camera.eyeWidth, 1u) * std::max(camera.eyeCount, 1u));
    const float height = float(std::max(camera.height, 1u));
    const float nearDistance = kProbeNearFraction * glm::length(scene.bounds.extent());
    for (uint32_t y = 0; y < gridY; ++y) {
        for (uint32_t x = 0; x < gridX; ++x) {
            const glm::vec2 pixel((float(x) + 0.5f) / float(gridX) * width,
                                  (float(y) + 0.5f) / float(gridY) * height);
            glm::vec3 origin, dir;
            primaryRay(camera, pixel, origin, dir);
            ++probe.rays;
            const Hit hit = closestHit(scene, bvh, origin, dir);
            if (!hit.found) continue;
            ++probe.hits;
            const glm::uvec3 tri = scene.mesh.triangles[hit.triangle];
            const glm::vec3& a = scene.mesh.positions[tri.x];
            const glm::vec3 normal =
                glm::cross(scene.mesh.positions[tri.y] - a, scene.mesh.positions[tri.z] - a);
            const uint32_t material = hit.triangle < scene.mesh.materialIds.size()
                                          ? scene.mesh.materialIds[hit.triangle]
                                          : 0u;
            const bool singleSided =
                material < scene.materials.size() && !scene.materials[material].doubleSided;
            const bool back = singleSided && glm::dot(normal, dir) > 0.0f;
            const bool close = hit.t < nearDistance;
            probe.backFaces += back ? 1u : 0u;
            probe.near += close ? 1u : 0u;
            probe.inside += back || close ? 1u : 0u;
        }
    }
    return probe;
}

}  // namespace fovea::scene
