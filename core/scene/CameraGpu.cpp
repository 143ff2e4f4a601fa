#include "core/scene/CameraGpu.h"

#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>

namespace fovea::scene::layout {

CameraInfo packCamera(const FrameCamera& camera, uint64_t frameIndex, uint64_t framesSinceReset) {
    CameraInfo out{};
    for (uint32_t e = 0; e < kMaxEyes; ++e) {
        // An unused second eye repeats the first so a stray read still sees a valid camera.
        const EyeView& eye = camera.eyes[e < camera.eyeCount ? e : 0];
        out.eyes[e].viewProj = eye.viewProj;
        out.eyes[e].prevViewProj = eye.prevViewProj;
        out.eyes[e].cameraToWorld = glm::inverse(eye.view);  // a rigid transform: always invertible
        out.eyes[e].position = glm::vec4(eye.position, float(eye.offsetX));
        out.eyes[e].gaze = glm::vec4(eye.gaze, eye.prevGaze);
    }
    out.size = {camera.eyeWidth, camera.height, camera.eyeCount, camera.cut ? 1u : 0u};
    const float aspect = camera.height > 0 ? float(camera.eyeWidth) / float(camera.height) : 1.0f;
    // Equirect: yfov = π has no finite tangent; 1 (a 90° view) keeps the passes that scale by it
    // (hit-distance normalization) finite. Rays and reprojection branch on frame.z instead.
    const bool equirect = camera.model == CameraModel::Equirect;
    out.jitter = {camera.jitter, equirect ? 1.0f : std::tan(0.5f * camera.yfov), aspect};
    out.frame = {uint32_t(frameIndex), uint32_t(framesSinceReset), uint32_t(camera.model), 0u};
    return out;
}

}  // namespace fovea::scene::layout
