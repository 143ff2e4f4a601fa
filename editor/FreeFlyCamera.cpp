#include "editor/FreeFlyCamera.h"

#include <algorithm>
#include <cmath>

namespace fovea::editor {

namespace {
constexpr float kMaxPitch = 89.0f * 3.14159265f / 180.0f;
constexpr glm::vec3 kWorldUp{0.0f, 1.0f, 0.0f};
}  // namespace

FreeFlyCamera::FreeFlyCamera(const scene::CameraDesc& pose)
    : mPosition(pose.position), mBase(pose) {
    const glm::vec3 toTarget = pose.target - pose.position;
    const float distance = glm::length(toTarget);
    // A degenerate pose (target on the camera) looks down -Z, as a default glTF camera does.
    const glm::vec3 f = distance > 1e-6f ? toTarget / distance : glm::vec3(0.0f, 0.0f, -1.0f);
    mPitch = std::clamp(std::asin(std::clamp(f.y, -1.0f, 1.0f)), -kMaxPitch, kMaxPitch);
    mYaw = std::atan2(f.x, -f.z);
    mFocus = distance > 1e-6f ? distance : 1.0f;
    mStep = std::max(1e-3f, mFocus * 0.02f);
}

glm::vec3 FreeFlyCamera::forward() const {
    return {std::cos(mPitch) * std::sin(mYaw), std::sin(mPitch),
            -std::cos(mPitch) * std::cos(mYaw)};
}

void FreeFlyCamera::move(const glm::vec3& local) {
    const glm::vec3 f = forward();
    // |pitch| < 89 degrees keeps f away from the world up: the cross product never vanishes.
    const glm::vec3 right = glm::normalize(glm::cross(f, kWorldUp));
    const glm::vec3 up = glm::cross(right, f);
    mPosition += right * local.x + up * local.y + f * local.z;
}

void FreeFlyCamera::look(float yawDegrees, float pitchDegrees) {
    mYaw += glm::radians(yawDegrees);
    mPitch = std::clamp(mPitch + glm::radians(pitchDegrees), -kMaxPitch, kMaxPitch);
}

scene::CameraDesc FreeFlyCamera::pose() const {
    scene::CameraDesc d = mBase;
    d.position = mPosition;
    d.target = mPosition + forward() * mFocus;
    d.up = kWorldUp;
    return d;
}

}  // namespace fovea::editor
