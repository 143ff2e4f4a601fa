// Bounding volume hierarchy over a TriangleMesh for the compute-shader ray tracer
// (shaders/common/bvh.glsl): a binned-SAH binary tree, flattened depth first into 32-byte nodes
// so the GPU walks it with a short fixed-size stack. Build details: docs/scene-gpu.md.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/scene/Scene.h"

namespace fovea::scene {

// One node as the GPU reads it (struct BvhNode in shaders/common/scene_data.glsl). Depth-first
// order puts an internal node's left child right after it, so only the right child is stored.
struct BvhNode {
    glm::vec3 boundsMin{0.0f};
    uint32_t index = 0;  // internal: right child node; leaf: first entry of Bvh::triangleOrder()
    glm::vec3 boundsMax{0.0f};
    uint32_t count = 0;  // leaf: triangle count (0 only for the root of an empty mesh);
                         // internal: kBvhInternalNode
    bool isLeaf() const;
};
static_assert(sizeof(BvhNode) == 32, "BvhNode must match the 32-byte GLSL struct");

// A count no leaf can have, so a leaf may legitimately hold zero triangles (empty mesh).
inline constexpr uint32_t kBvhInternalNode = 0xFFFFFFFFu;
inline bool BvhNode::isLeaf() const {
    return count != kBvhInternalNode;
}

struct BvhBuildOptions {
    uint32_t bins = 16;             // SAH bins per axis, clamped to [2, 64]
    uint32_t maxLeafSize = 4;       // clamped to [1, 16]; larger nodes are always split
    float traversalCost = 1.0f;     // SAH cost of visiting one node...
    float intersectionCost = 1.0f;  // ...relative to intersecting one triangle
};

struct BvhStats {
    uint32_t triangleCount = 0;     // of the input mesh
    uint32_t invalidTriangles = 0;  // with a non-finite vertex: in no leaf (never hittable)
    uint32_t nodeCount = 0;
    uint32_t leafCount = 0;
    uint32_t maxDepth = 0;  // root = 0
    uint32_t maxLeafTriangles = 0;
    double averageLeafTriangles = 0.0;
    double sahCost = 0.0;  // expected cost of a random ray, in intersectionCost units
    double buildMs = 0.0;
};

class Bvh {
public:
    // The GPU traversal stack holds at most one entry per level, so the build caps the depth
    // (switching to object-median splits near the cap) and the shader sizes its stack by it.
    // Must equal kBvhMaxDepth in shaders/common/scene_data.glsl.
    static constexpr uint32_t kMaxDepth = 48;

    // Throws RuntimeError when a triangle references a vertex that does not exist or the mesh
    // has more triangles than 32-bit node indices can address. Degenerate input (coincident or
    // zero-area triangles, huge coordinates) builds a valid tree; triangles with a NaN/Inf vertex
    // are left out of every leaf and ordered last.
    explicit Bvh(const TriangleMesh& mesh, const BvhBuildOptions& options = {});

    // nodes()[0] is the root. Never empty.
    const std::vector<BvhNode>& nodes() const { return mNodes; }
    // triangleOrder()[i] = mesh triangle stored at position i of the GPU triangle arrays; leaves
    // index this order. A permutation of all mesh triangles (invalid ones at the end).
    const std::vector<uint32_t>& triangleOrder() const { return mOrder; }
    const BvhStats& stats() const { return mStats; }
    // Of all valid triangles (empty when there are none).
    const Bounds& bounds() const { return mBounds; }

private:
    struct Builder;
    std::vector<BvhNode> mNodes;
    std::vector<uint32_t> mOrder;
    BvhStats mStats;
    Bounds mBounds;
};

}  // namespace fovea::scene
