// A cheap CPU look through the camera: a coarse grid of primary rays traced through the scene's
// BVH, so `fovea run` can say when a picture shows nothing (no ray hits geometry) or when the
// camera is probably inside geometry — both give a black or meaningless image with exit 0.
// Runs on the CPU between frames (never in the GPU-timed frames) and is independent of the
// graph (a graph without GBuffer is checked too).
//
// "Inside" heuristic (docs/scenes.md): a probe ray counts as inside when its first hit is
//  - the back face (by the glTF winding, §3.7.2.1: counter-clockwise = front) of a single-sided
//    material — closed single-sided objects face outwards, so from within one every ray meets a
//    back face — or
//  - closer than kProbeNearFraction of the scene's bounding-box diagonal (the camera sits in or
//    against a surface, whatever its sidedness).
// A view is flagged when at least half of the probe rays are "inside".
#pragma once
#include <cstdint>

#include "core/scene/Bvh.h"
#include "core/scene/Camera.h"
#include "core/scene/Scene.h"

namespace fovea::scene {

inline constexpr float kProbeNearFraction = 1e-3f;
inline constexpr double kProbeInsideFlag = 0.5;  // share of "inside" rays that flags a view

struct ViewProbe {
    uint32_t gridX = 0, gridY = 0;  // rays across the whole (side-by-side) image
    uint32_t rays = 0;
    uint32_t hits = 0;       // rays that hit a triangle
    uint32_t backFaces = 0;  // first hit: back face of a single-sided material
    uint32_t near = 0;       // first hit closer than kProbeNearFraction * scene diagonal
    uint32_t inside = 0;     // backFaces or near (a ray counts once)
    double hitFraction() const { return rays ? double(hits) / rays : 0.0; }
    double insideFraction() const { return rays ? double(inside) / rays : 0.0; }
    bool looksInside() const { return rays && insideFraction() >= kProbeInsideFlag; }
};

// Traces gridX x gridY primary rays through pixel centres spread evenly over the camera's image
// (all eyes), with the rays of primaryRay (shaders/common/camera.glsl). `bvh` must be built from
// `scene.mesh`.
ViewProbe probeView(const Scene& scene, const Bvh& bvh, const FrameCamera& camera,
                    uint32_t gridX = 32, uint32_t gridY = 32);

}  // namespace fovea::scene
