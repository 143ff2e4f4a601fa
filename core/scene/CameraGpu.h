// The per-frame camera as shaders see it: the uniform block `camera_info` declared by
// shaders/common/camera.glsl, mirrored field by field here (std140). The render graph owns one
// host-visible buffer, refreshes it before every frame and binds it to any pipeline that
// declares it (GraphExecuteContext::bindFields), so passes never pack cameras themselves.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>

#include "core/scene/Camera.h"

namespace fovea::scene::layout {

struct CameraEye {
    glm::mat4 viewProj;       // jitter-free; the jitter moves pixel positions (camera.glsl)
    glm::mat4 prevViewProj;   // previous frame's viewProj (motion vectors)
    glm::mat4 cameraToWorld;  // inverse view: columns are right, up, back, position
    glm::vec4 position;       // xyz eye position; w = first column of this eye (offsetX)
    glm::vec4 gaze;           // xy gaze in [0,1]^2 of the eye's image; zw the previous frame's
};

struct CameraInfo {
    CameraEye eyes[kMaxEyes];
    glm::uvec4 size;   // x eye width, y height, z eye count, w cut (0/1)
    glm::vec4 jitter;  // xy sub-pixel jitter in pixels; z tan(yfov/2); w eye aspect (w/h)
    glm::uvec4 frame;  // x frame index (low 32 bits), y frames since reset (low 32), z model, w 0
};

static_assert(sizeof(CameraEye) == 224);
static_assert(sizeof(CameraInfo) == 2 * 224 + 48);

CameraInfo packCamera(const FrameCamera& camera, uint64_t frameIndex, uint64_t framesSinceReset);

}  // namespace fovea::scene::layout
