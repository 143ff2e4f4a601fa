#include "core/scene/Tangents.h"

#include <cmath>

namespace fovea::scene {

glm::vec3 perpendicularTo(const glm::vec3& n) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);  // |sign + n.z| >= 1 for a unit n
    const float b = n.x * n.y * a;
    return {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
}

std::vector<glm::vec4> generateTangents(const std::vector<glm::vec3>& positions,
                                        const std::vector<glm::vec3>& normals,
                                        const std::vector<glm::vec2>& uvs,
                                        const std::vector<glm::uvec3>& triangles) {
    const size_t n = positions.size();
    std::vector<glm::dvec3> tangent(n, glm::dvec3(0.0)), bitangent(n, glm::dvec3(0.0));
    for (const glm::uvec3& t : triangles) {
        if (t.x >= n || t.y >= n || t.z >= n) continue;
        const glm::dvec3 e1 = glm::dvec3(positions[t.y]) - glm::dvec3(positions[t.x]);
        const glm::dvec3 e2 = glm::dvec3(positions[t.z]) - glm::dvec3(positions[t.x]);
        const glm::dvec2 d1 = glm::dvec2(uvs[t.y]) - glm::dvec2(uvs[t.x]);
        const glm::dvec2 d2 = glm::dvec2(uvs[t.z]) - glm::dvec2(uvs[t.x]);
        const double det = d1.x * d2.y - d2.x * d1.y;
        if (!(std::abs(det) > 1e-20) || !std::isfinite(det)) continue;  // UVs without area
        // dP/du and dP/dv times |det| (twice the UV area): larger triangles weigh more (by area
        // where the UV density is even), and no division by a small determinant.
        const double sign = det > 0.0 ? 1.0 : -1.0;
        const glm::dvec3 sdir = (e1 * d2.y - e2 * d1.y) * sign;
        const glm::dvec3 tdir = (e2 * d1.x - e1 * d2.x) * sign;
        for (uint32_t v : {t.x, t.y, t.z}) {
            tangent[v] += sdir;
            bitangent[v] += tdir;
        }
    }
    std::vector<glm::vec4> out(n);
    for (size_t i = 0; i < n; ++i) {
        const glm::dvec3 nn = glm::dvec3(normals[i]);
        glm::dvec3 t = tangent[i] - nn * glm::dot(nn, tangent[i]);  // Gram-Schmidt
        const double length = glm::length(t);
        if (!(length > 1e-12) || !std::isfinite(length)) {
            out[i] = glm::vec4(perpendicularTo(normals[i]), 1.0f);
            continue;
        }
        t /= length;
        const double w = glm::dot(glm::cross(nn, t), bitangent[i]) < 0.0 ? -1.0 : 1.0;
        out[i] = glm::vec4(glm::vec3(t), float(w));
    }
    return out;
}

}  // namespace fovea::scene
