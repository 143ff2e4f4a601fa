// Ray queries against the scene BVH (core/scene/Bvh.h) in plain compute: lavapipe has no
// ray-tracing extensions. Closest hit walks near child first with a stack of far children and
// their entry distances; occlusion stops at the first hit. Triangles: Moeller-Trumbore in its
// division-free form (one division per accepted hit). Rays are `origin + t * direction` with
// 0 <= tMin < tMax; the direction need not be normalized (t is in its units).
//
// Alpha-tested materials (SCENE_HAS_ALPHA, glTF MASK / BLEND): a candidate hit on a triangle
// flagged in v0.w runs scene_sample.glsl's any-hit test and is skipped where the ray passes
// through. `alphaSeed` picks BLEND's random decisions: callers hash it per ray (pixel, frame,
// sample, bounce) so reruns are bit-identical; the overloads without it hash the ray itself.
// SCENE_HAS_ALPHA 0 compiles the test out: queries in opaque scenes are the code they were.
#ifndef FOVEA_BVH_GLSL
#define FOVEA_BVH_GLSL

#include "scene_data.glsl"
#if SCENE_HAS_ALPHA
#include "random.glsl"
#include "scene_sample.glsl"  // sceneAlphaPassesThrough (materials, textures, vertex colours)
#endif

const uint kBvhNoHit = 0xFFFFFFFFu;
const float kBvhMiss = 3.4e38;  // box entry distance reported for a miss

struct BvhHit {
    float t;
    uint triangle;      // GPU triangle index (scene_triangles), kBvhNoHit on a miss
    vec2 barycentrics;  // weights of vertices 1 and 2; vertex 0 gets 1 - x - y
};

// 1 / direction with zero components replaced by a tiny signed value, so slab distances are
// never 0 * inf = NaN (they may be +-inf, which the min/max logic handles).
vec3 bvhSafeInverse(vec3 d) {
    const float kTiny = 1e-30;
    vec3 safe = vec3(abs(d.x) < kTiny ? (d.x < 0.0 ? -kTiny : kTiny) : d.x,
                     abs(d.y) < kTiny ? (d.y < 0.0 ? -kTiny : kTiny) : d.y,
                     abs(d.z) < kTiny ? (d.z < 0.0 ? -kTiny : kTiny) : d.z);
    return 1.0 / safe;  // |safe| >= kTiny on every axis
}

// Entry distance of the ray into [bmin, bmax] clipped to [tMin, tMax], or kBvhMiss. The far
// distance is widened by a few ulps (pbrt's 1 + 2 gamma(3)) so rounding in the slab products
// never rejects a box whose face holds the triangle the ray hits.
float bvhBoxEntry(vec3 bmin, vec3 bmax, vec3 origin, vec3 invDir, float tMin, float tMax) {
    vec3 t0 = (bmin - origin) * invDir;
    vec3 t1 = (bmax - origin) * invDir;
    vec3 tNear3 = min(t0, t1);
    vec3 tFar3 = max(t0, t1);
    float tNear = max(max(tNear3.x, tNear3.y), max(tNear3.z, tMin));
    float tFar = min(min(tFar3.x, tFar3.y), min(tFar3.z, tMax)) * 1.0000004;
    return tNear <= tFar ? tNear : kBvhMiss;
}

// Ray vs triangle (v0, e1 = v1 - v0, e2 = v2 - v0). Edges count as inside and are widened by a
// relative slack of kBvhEdgeSlack: Moeller-Trumbore is not watertight (the two triangles of a
// shared edge compute it from different vertices and edges, and a slightly non-planar quad
// rounds both ways), so without slack a ray exactly through a shared edge could miss both and
// see through a wall. With it, such a ray hits at least one; barycentrics are clamped back into
// the triangle. On a hit in (tMin, tMax) returns true with t and barycentrics; degenerate
// triangles and rays in the triangle's plane never hit.
const float kBvhEdgeSlack = 1e-6;
bool bvhIntersectTriangle(vec3 origin, vec3 direction, vec3 v0, vec3 e1, vec3 e2, float tMin,
                          float tMax, out float t, out vec2 barycentrics) {
    t = 0.0;
    barycentrics = vec2(0.0);
    vec3 p = cross(direction, e2);
    float det = dot(e1, p);
    float s = det < 0.0 ? -1.0 : 1.0;
    float absDet = abs(det);
    vec3 tv = origin - v0;
    float u = dot(tv, p) * s;
    float slack = kBvhEdgeSlack * absDet;
    // Written as positive tests so NaN (from huge coordinates) rejects.
    if (!(u >= -slack && u <= absDet + slack)) return false;
    vec3 q = cross(tv, e1);
    float v = dot(direction, q) * s;
    if (!(v >= -slack && u + v <= absDet + slack)) return false;
    float tScaled = dot(e2, q) * s;
    if (!(absDet > 0.0)) return false;
    float inv = 1.0 / absDet;  // absDet > 0; a denormal may give inf, then t is inf or NaN and
                               // fails the range test below
    float tt = tScaled * inv;
    if (!(tt > tMin && tt < tMax)) return false;
    t = tt;
    vec2 b = clamp(vec2(u, v) * inv, 0.0, 1.0);
    barycentrics = b.x + b.y > 1.0 ? b / (b.x + b.y) : b;  // b.x + b.y > 1 > 0 here
    return true;
}

bool bvhIntersectStoredTriangle(uint triangle, vec3 origin, vec3 direction, float tMin,
                                float tMax, out float t, out vec2 barycentrics) {
    uint base = 3u * triangle;
    return bvhIntersectTriangle(origin, direction, sceneBvhPosition(base).xyz,
                                sceneBvhPosition(base + 1u).xyz,
                                sceneBvhPosition(base + 2u).xyz, tMin, tMax, t,
                                barycentrics);
}

#if SCENE_HAS_ALPHA
// A candidate hit the ray passes through (alpha test). v0.w was loaded with the triangle's
// vertices: triangles of opaque materials (0) stop here without a material lookup.
bool bvhPassesThrough(uint triangle, vec2 barycentrics, uint alphaSeed) {
    return sceneBvhPosition(3u * triangle).w != 0.0 &&
           sceneAlphaPassesThrough(triangle, barycentrics, alphaSeed);
}
#endif

// The seed of the overloads without one: a hash of the ray's bits, so distinct rays decide
// independently and the same ray decides the same way.
uint bvhRaySeed(vec3 origin, vec3 direction) {
#if SCENE_HAS_ALPHA
    uvec3 o = floatBitsToUint(origin), d = floatBitsToUint(direction);
    return hashCombine(hashCombine(hashCombine(pcgHash(o.x), o.y), o.z),
                       hashCombine(hashCombine(pcgHash(d.x), d.y), d.z));
#else
    return 0u;  // unused: nothing is alpha-tested
#endif
}

// Closest triangle hit in (tMin, tMax) that the ray does not pass through. On a miss returns
// false and hit.triangle = kBvhNoHit.
bool bvhClosestHit(vec3 origin, vec3 direction, float tMin, float tMax, uint alphaSeed,
                   out BvhHit hit) {
    hit.t = tMax;
    hit.triangle = kBvhNoHit;
    hit.barycentrics = vec2(0.0);
    vec3 invDir = bvhSafeInverse(direction);
    BvhNode root = sceneBvhNode(0);
    if (bvhBoxEntry(root.boundsMin, root.boundsMax, origin, invDir, tMin, tMax) == kBvhMiss)
        return false;

    // Entries <= depth of the current node <= kBvhMaxDepth (the build caps the depth), so
    // the stack cannot overflow; the bound check only guards against a corrupt buffer.
    uint stackNode[kBvhMaxDepth];
    float stackEntry[kBvhMaxDepth];
    uint sp = 0u;
    uint nodeIndex = 0u;
    while (true) {
        BvhNode node = sceneBvhNode(nodeIndex);
        if (node.count != kBvhInternalNode) {
            for (uint i = node.index; i < node.index + node.count; ++i) {
                float t;
                vec2 bary;
                // The alpha test only where it is compiled in, so that opaque scenes get the
                // very same instructions as before it existed.
                if (bvhIntersectStoredTriangle(i, origin, direction, tMin, hit.t, t, bary)
#if SCENE_HAS_ALPHA
                    && !bvhPassesThrough(i, bary, alphaSeed)
#endif
                ) {
                    hit.t = t;
                    hit.triangle = i;
                    hit.barycentrics = bary;
                }
            }
        } else {
            uint left = nodeIndex + 1u;
            uint right = node.index;
            BvhNode l = sceneBvhNode(left);
            BvhNode r = sceneBvhNode(right);
            float tl = bvhBoxEntry(l.boundsMin, l.boundsMax, origin, invDir, tMin, hit.t);
            float tr = bvhBoxEntry(r.boundsMin, r.boundsMax, origin, invDir, tMin, hit.t);
            bool hitL = tl != kBvhMiss;
            bool hitR = tr != kBvhMiss;
            if (hitL && hitR) {
                bool leftFirst = tl <= tr;
                if (sp < kBvhMaxDepth) {
                    stackNode[sp] = leftFirst ? right : left;
                    stackEntry[sp] = leftFirst ? tr : tl;
                    ++sp;
                }
                nodeIndex = leftFirst ? left : right;
                continue;
            }
            if (hitL || hitR) {
                nodeIndex = hitL ? left : right;
                continue;
            }
        }
        // Pop the nearest pending subtree that can still hold a closer hit.
        bool found = false;
        while (sp > 0u && !found) {
            --sp;
            if (stackEntry[sp] <= hit.t) {
                nodeIndex = stackNode[sp];
                found = true;
            }
        }
        if (!found) break;
    }
    return hit.triangle != kBvhNoHit;
}

bool bvhClosestHit(vec3 origin, vec3 direction, float tMin, float tMax, out BvhHit hit) {
    return bvhClosestHit(origin, direction, tMin, tMax, bvhRaySeed(origin, direction), hit);
}

// True when any triangle the ray does not pass through lies on it within (tMin, tMax): shadow
// rays pass the light's distance (slightly shortened) as tMax.
bool bvhOccluded(vec3 origin, vec3 direction, float tMin, float tMax, uint alphaSeed) {
    vec3 invDir = bvhSafeInverse(direction);
    uint stackNode[kBvhMaxDepth];
    uint sp = 0u;
    BvhNode root = sceneBvhNode(0);
    if (bvhBoxEntry(root.boundsMin, root.boundsMax, origin, invDir, tMin, tMax) == kBvhMiss)
        return false;
    uint nodeIndex = 0u;
    while (true) {
        BvhNode node = sceneBvhNode(nodeIndex);
        if (node.count != kBvhInternalNode) {
            for (uint i = node.index; i < node.index + node.count; ++i) {
                float t;
                vec2 bary;
                if (bvhIntersectStoredTriangle(i, origin, direction, tMin, tMax, t, bary)
#if SCENE_HAS_ALPHA
                    && !bvhPassesThrough(i, bary, alphaSeed)
#endif
                )
                    return true;
            }
        } else {
            uint left = nodeIndex + 1u;
            uint right = node.index;
            BvhNode l = sceneBvhNode(left);
            BvhNode r = sceneBvhNode(right);
            bool hitL =
                bvhBoxEntry(l.boundsMin, l.boundsMax, origin, invDir, tMin, tMax) != kBvhMiss;
            bool hitR =
                bvhBoxEntry(r.boundsMin, r.boundsMax, origin, invDir, tMin, tMax) != kBvhMiss;
            if (hitL && hitR) {
                if (sp < kBvhMaxDepth) stackNode[sp++] = right;  // see bvhClosestHit
                nodeIndex = left;
                continue;
            }
            if (hitL || hitR) {
                nodeIndex = hitL ? left : right;
                continue;
            }
        }
        if (sp == 0u) break;
        nodeIndex = stackNode[--sp];
    }
    return false;
}

bool bvhOccluded(vec3 origin, vec3 direction, float tMin, float tMax) {
    return bvhOccluded(origin, direction, tMin, tMax, bvhRaySeed(origin, direction));
}

// Origin for a ray leaving a surface at p with geometric normal n (pointing to the side the
// ray leaves from): Waechter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection"
// (Ray Tracing Gems, ch. 6). Integer ulp offsets scale with |p|, so it works at any scene scale;
// rays then use tMin = 0.
vec3 bvhOffsetRay(vec3 p, vec3 n) {
    const float kOrigin = 1.0 / 32.0;
    const float kFloatScale = 1.0 / 65536.0;
    const float kIntScale = 256.0;
    ivec3 ofi = ivec3(kIntScale * n);
    vec3 pi = vec3(intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0 ? -ofi.x : ofi.x)),
                   intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0 ? -ofi.y : ofi.y)),
                   intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0 ? -ofi.z : ofi.z)));
    return vec3(abs(p.x) < kOrigin ? p.x + kFloatScale * n.x : pi.x,
                abs(p.y) < kOrigin ? p.y + kFloatScale * n.y : pi.y,
                abs(p.z) < kOrigin ? p.z + kFloatScale * n.z : pi.z);
}

#endif
