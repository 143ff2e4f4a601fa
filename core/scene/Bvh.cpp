#include "core/scene/Bvh.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <future>
#include <limits>
#include <string>
#include <thread>

#include "core/util/Error.h"

namespace fovea::scene {
namespace {

constexpr uint32_t kMaxBins = 64;
constexpr uint32_t kMaxLeafLimit = 16;
// Below this many triangles a subtree is built on the calling thread (a thread costs more).
constexpr uint32_t kParallelTriangles = 65536;

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Half the surface area, in double: float boxes near 1e20 would overflow a float product, and
// the SAH only compares ratios. An empty box has no area.
double halfArea(const glm::vec3& mn, const glm::vec3& mx) {
    if (mn.x > mx.x) return 0.0;
    const double dx = double(mx.x) - mn.x, dy = double(mx.y) - mn.y, dz = double(mx.z) - mn.z;
    return dx * dy + dy * dz + dz * dx;
}

struct Box {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{-std::numeric_limits<float>::max()};
    void grow(const glm::vec3& mn, const glm::vec3& mx) {
        min = glm::min(min, mn);
        max = glm::max(max, mx);
    }
    void grow(const Box& b) { grow(b.min, b.max); }
    double area() const { return halfArea(min, max); }
};

// Levels an object-median subtree over n triangles needs until every leaf fits maxLeaf:
// the smallest k with n <= maxLeaf * 2^k.
uint32_t medianLevels(uint32_t n, uint32_t maxLeaf) {
    uint32_t k = 0;
    uint64_t capacity = maxLeaf;
    while (capacity < n) {
        capacity *= 2;
        ++k;
    }
    return k;
}

}  // namespace

struct Bvh::Builder {
    Builder(std::vector<uint32_t>& orderOut, const BvhBuildOptions& options)
        : order(orderOut),
          bins(std::clamp(options.bins, 2u, kMaxBins)),
          maxLeaf(std::clamp(options.maxLeafSize, 1u, kMaxLeafLimit)),
          traversalCost(std::max(0.0f, options.traversalCost)),
          intersectionCost(std::max(1e-6f, options.intersectionCost)) {}

    std::vector<glm::vec3> triMin, triMax, centroid;  // per mesh triangle
    std::vector<uint32_t>& order;
    uint32_t bins;
    uint32_t maxLeaf;
    double traversalCost;
    double intersectionCost;

    // Bin of a centroid coordinate; the same expression classifies during binning and
    // partitioning, so both always agree. scale is finite: extent > 0 was checked.
    uint32_t binOf(float c, double cmin, double scale) const {
        const double b = (double(c) - cmin) * scale;
        return std::min(bins - 1, static_cast<uint32_t>(b));
    }

    // Builds the subtree over order[begin, end) depth first into `out` (indices relative to
    // out's start). For `spawnLevels` more levels, a node over at least kParallelTriangles
    // builds its left subtree on another thread into its own array, then both are appended with
    // their child indices shifted: the same splits in the same order, so the tree is identical to
    // a one-thread build (the partitions touch disjoint ranges of `order`).
    void build(uint32_t begin, uint32_t end, uint32_t depth, std::vector<BvhNode>& nodes,
               uint32_t spawnLevels) {
        const uint32_t nodeIndex = static_cast<uint32_t>(nodes.size());
        nodes.emplace_back();
        Box box, centroids;
        for (uint32_t i = begin; i < end; ++i) {
            const uint32_t t = order[i];
            box.grow(triMin[t], triMax[t]);
            centroids.grow(centroid[t], centroid[t]);
        }
        nodes[nodeIndex].boundsMin = box.min;
        nodes[nodeIndex].boundsMax = box.max;
        const uint32_t n = end - begin;

        auto makeLeaf = [&] {
            nodes[nodeIndex].index = begin;
            nodes[nodeIndex].count = n;
        };
        if (n <= 1) return makeLeaf();

        uint32_t mid = begin;
        // Depth cap (see kMaxDepth): once the remaining depth budget only just suffices for
        // median splits, take them; they halve the count, so every leaf ends at <= kMaxDepth.
        const uint32_t levels = medianLevels(n, maxLeaf);
        if (depth + levels >= kMaxDepth) {
            if (levels == 0) return makeLeaf();
            mid = medianSplit(begin, end, centroids);
        } else {
            mid = sahSplit(begin, end, box, centroids);
            if (mid == begin) {
                if (n <= maxLeaf) return makeLeaf();
                // No useful plane (all centroids coincide) but too many triangles for a leaf.
                mid = medianSplit(begin, end, centroids);
            }
        }
        nodes[nodeIndex].count = kBvhInternalNode;
        if (spawnLevels > 0 && n >= kParallelTriangles) {
            std::vector<BvhNode> left, right;
            auto leftTask = std::async(std::launch::async, [&] {
                build(begin, mid, depth + 1, left, spawnLevels - 1);
            });
            build(mid, end, depth + 1, right, spawnLevels - 1);
            leftTask.get();
            appendSubtree(nodes, left);
            nodes[nodeIndex].index = static_cast<uint32_t>(nodes.size());
            appendSubtree(nodes, right);
            return;
        }
        build(begin, mid, depth + 1, nodes, 0);
        nodes[nodeIndex].index = static_cast<uint32_t>(nodes.size());
        build(mid, end, depth + 1, nodes, 0);
    }

    static void appendSubtree(std::vector<BvhNode>& out, const std::vector<BvhNode>& subtree) {
        const uint32_t offset = static_cast<uint32_t>(out.size());
        for (BvhNode node : subtree) {
            if (!node.isLeaf()) node.index += offset;  // a leaf's index is into order: global
            out.push_back(node);
        }
    }

    // Splits [begin, end) at its middle along the widest centroid axis. Always returns a
    // position strictly inside the range (n >= 2), so recursion terminates even for
    // coincident triangles.
    uint32_t medianSplit(uint32_t begin, uint32_t end, const Box& centroids) {
        const glm::vec3 ext = centroids.max - centroids.min;
        const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
        const uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(
            order.begin() + begin, order.begin() + mid, order.begin() + end,
            [&](uint32_t a, uint32_t b) { return centroid[a][axis] < centroid[b][axis]; });
        return mid;
    }

    // Binned SAH over all three axes. Returns the partition point, or `begin` when keeping a
    // leaf is cheaper or no plane separates the centroids (the caller decides).
    uint32_t sahSplit(uint32_t begin, uint32_t end, const Box& box, const Box& centroids) {
        struct Bin {
            Box box;
            uint32_t count = 0;
        };
        const uint32_t n = end - begin;
        double bestCost = std::numeric_limits<double>::infinity();
        int bestAxis = -1;
        uint32_t bestBin = 0;
        std::array<Bin, kMaxBins> binArray;
        std::array<double, kMaxBins> rightArea;
        std::array<uint32_t, kMaxBins> rightCount;
        for (int axis = 0; axis < 3; ++axis) {
            const double cmin = centroids.min[axis];
            const double extent = double(centroids.max[axis]) - cmin;
            if (!(extent > 0.0)) continue;  // every centroid on one plane: nothing to split
            const double scale = double(bins) / extent;
            std::fill(binArray.begin(), binArray.begin() + bins, Bin{});
            for (uint32_t i = begin; i < end; ++i) {
                const uint32_t t = order[i];
                Bin& b = binArray[binOf(centroid[t][axis], cmin, scale)];
                b.box.grow(triMin[t], triMax[t]);
                ++b.count;
            }
            // Right-to-left sweep: what lies at or beyond bin i.
            Box accum;
            uint32_t count = 0;
            for (uint32_t i = bins - 1; i > 0; --i) {
                accum.grow(binArray[i].box);
                count += binArray[i].count;
                rightArea[i] = accum.area();
                rightCount[i] = count;
            }
            accum = Box{};
            count = 0;
            for (uint32_t i = 1; i < bins; ++i) {
                accum.grow(binArray[i - 1].box);
                count += binArray[i - 1].count;
                if (count == 0 || rightCount[i] == 0) continue;
                const double cost = accum.area() * count + rightArea[i] * rightCount[i];
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = axis;
                    bestBin = i;
                }
            }
        }
        if (bestAxis < 0) return begin;

        // A zero-area node (all triangles on one line or point) makes area ratios meaningless;
        // then treat both children as hit by every ray: splitting only pays when forced.
        const double area = box.area();
        const double splitCost =
            traversalCost + intersectionCost * (area > 0.0 ? bestCost / area : double(n));
        const double leafCost = intersectionCost * n;
        if (n <= maxLeaf && leafCost <= splitCost) return begin;

        const double cmin = centroids.min[bestAxis];
        const double scale = double(bins) / (double(centroids.max[bestAxis]) - cmin);
        auto it = std::partition(order.begin() + begin, order.begin() + end, [&](uint32_t t) {
            return binOf(centroid[t][bestAxis], cmin, scale) < bestBin;
        });
        // Both sides are non-empty: the chosen plane had triangles on each side when binned with
        // the same binOf().
        return static_cast<uint32_t>(it - order.begin());
    }
};

Bvh::Bvh(const TriangleMesh& mesh, const BvhBuildOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const size_t triangleCount = mesh.triangles.size();
    // Node indices are 32-bit and a tree has < 2n nodes.
    if (triangleCount >= (size_t(1) << 31))
        throw RuntimeError("Bvh: " + std::to_string(triangleCount) +
                           " triangles exceed the 2^31 a 32-bit node index can address");
    const uint32_t n = static_cast<uint32_t>(triangleCount);
    mStats.triangleCount = n;

    Builder builder(mOrder, options);
    builder.triMin.resize(n);
    builder.triMax.resize(n);
    builder.centroid.resize(n);
    std::vector<uint32_t> invalid;
    mOrder.reserve(n);
    const size_t vertexCount = mesh.positions.size();
    for (uint32_t t = 0; t < n; ++t) {
        const glm::uvec3& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k)
            if (tri[k] >= vertexCount)
                throw RuntimeError("Bvh: triangle " + std::to_string(t) + " references vertex " +
                                   std::to_string(tri[k]) + " but the mesh has " +
                                   std::to_string(vertexCount));
        const glm::vec3 &a = mesh.positions[tri.x], &b = mesh.positions[tri.y],
                        &c = mesh.positions[tri.z];
        if (!finite(a) || !finite(b) || !finite(c)) {
            invalid.push_back(t);
            continue;
        }
        builder.triMin[t] = glm::min(a, glm::min(b, c));
        builder.triMax[t] = glm::max(a, glm::max(b, c));
        // Halves first: min + max overflows for coordinates near FLT_MAX.
        builder.centroid[t] = builder.triMin[t] * 0.5f + builder.triMax[t] * 0.5f;
        mOrder.push_back(t);
    }
    const uint32_t validCount = static_cast<uint32_t>(mOrder.size());
    mStats.invalidTriangles = static_cast<uint32_t>(invalid.size());

    mNodes.reserve(size_t(validCount) * 2 + 1);
    // Threads: one subtree per core at the top of the tree (2 cores: 2 levels, 4 subtrees, so
    // an uneven split still keeps both busy).
    const uint32_t threads = std::max(1u, std::thread::hardware_concurrency());
    uint32_t spawnLevels = 0;
    while ((1u << spawnLevels) < threads * 2 && spawnLevels < 6) ++spawnLevels;
    builder.build(0, validCount, 0, mNodes, threads > 1 ? spawnLevels : 0);
    mOrder.insert(mOrder.end(), invalid.begin(), invalid.end());
    mNodes.shrink_to_fit();
    if (validCount > 0) {
        mBounds.min = mNodes[0].boundsMin;
        mBounds.max = mNodes[0].boundsMax;
    }

    // Statistics from the flat array: depth via an explicit walk (the array is depth first).
    mStats.nodeCount = static_cast<uint32_t>(mNodes.size());
    const double rootArea = halfArea(mNodes[0].boundsMin, mNodes[0].boundsMax);
    std::vector<std::pair<uint32_t, uint32_t>> stack{{0u, 0u}};
    uint64_t leafTriangles = 0;
    while (!stack.empty()) {
        auto [index, depth] = stack.back();
        stack.pop_back();
        const BvhNode& node = mNodes[index];
        mStats.maxDepth = std::max(mStats.maxDepth, depth);
        const double areaRatio =
            rootArea > 0.0 ? halfArea(node.boundsMin, node.boundsMax) / rootArea : 1.0;
        if (node.isLeaf()) {
            ++mStats.leafCount;
            leafTriangles += node.count;
            mStats.maxLeafTriangles = std::max(mStats.maxLeafTriangles, node.count);
            mStats.sahCost += builder.intersectionCost * node.count * areaRatio;
        } else {
            mStats.sahCost += builder.traversalCost * areaRatio;
            stack.push_back({index + 1, depth + 1});
            stack.push_back({node.index, depth + 1});
        }
    }
    mStats.averageLeafTriangles = mStats.leafCount ? double(leafTriangles) / mStats.leafCount : 0;
    mStats.buildMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace fovea::scene
