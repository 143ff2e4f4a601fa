#include "core/scene/Camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace fovea::scene {
namespace {

float radicalInverse(uint64_t index, uint32_t base) {
    float inverse = 1.0f / float(base), fraction = inverse, result = 0.0f;
    while (index > 0) {
        result += float(index % base) * fraction;
        index /= base;
        fraction *= inverse;
    }
    return result;
}

// A look-at basis that stays defined when `up` is parallel to the view direction or the target
// equals the position (both possible in hand-written camera paths).
glm::mat4 safeLookAt(const glm::vec3& position, const glm::vec3& target, const glm::vec3& up) {
    glm::vec3 forward = target - position;
    if (glm::dot(forward, forward) < 1e-20f) forward = glm::vec3(0, 0, -1);
    forward = glm::normalize(forward);  // length checked above
    glm::vec3 u = up;
    if (glm::dot(u, u) < 1e-20f || glm::length(glm::cross(forward, glm::normalize(u))) < 1e-4f)
        u = std::abs(forward.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    return glm::lookAtRH(position, position + forward, u);
}

}  // namespace

const char* cameraModelName(CameraModel model) {
    return model == CameraModel::Equirect ? "equirect" : "perspective";
}

std::optional<CameraModel> parseCameraModel(const std::string& name) {
    if (name == "perspective") return CameraModel::Perspective;
    if (name == "equirect") return CameraModel::Equirect;
    return std::nullopt;
}

glm::vec3 equirectDirection(glm::vec2 uv) {
    const float pi = 3.14159265358979f;
    const float longitude = (uv.x - 0.5f) * 2.0f * pi, latitude = (0.5f - uv.y) * pi;
    const float c = std::cos(latitude);
    return {c * std::sin(longitude), std::sin(latitude), -c * std::cos(longitude)};
}

glm::vec2 equirectUv(glm::vec3 d) {
    const float pi = 3.14159265358979f;
    const float len = glm::length(d);
    if (!(len > 0.0f)) return glm::vec2(0.5f);  // no direction: the centre, never NaN
    d /= len;
    // atan2(x, -z) is defined for (0, 0) (returns 0): the poles map to u = 0.5.
    const float longitude = std::atan2(d.x, -d.z);
    const float latitude = std::asin(std::clamp(d.y, -1.0f, 1.0f));
    return {longitude / (2.0f * pi) + 0.5f, 0.5f - latitude / pi};
}

EyeSplit splitEyes(uint32_t width, int eyesParam, uint32_t cameraEyes) {
    int eyes = eyesParam > 0 ? eyesParam : int(std::clamp(cameraEyes, 1u, kMaxEyes));
    if (eyes > int(width)) eyes = 1;  // a 1-pixel-wide image cannot be split
    return {eyes, std::max(int(width) / eyes, 1)};
}

glm::vec2 halton23(uint64_t index) {
    // Index 0 of the sequence is (0,0); start at 1 so frame 0 is already off-centre.
    return {radicalInverse(index + 1, 2), radicalInverse(index + 1, 3)};
}

FrameCamera makeFrameCamera(const CameraDesc& camera, uint32_t width, uint32_t height,
                            const CameraRigOptions& rig, uint64_t frameIndex,
                            const FrameCamera* previous, const glm::vec2 gaze[kMaxEyes]) {
    FrameCamera out;
    out.eyeCount = rig.stereo ? 2u : 1u;
    out.height = std::max(1u, height);
    out.model = rig.model;
    const bool equirect = rig.model == CameraModel::Equirect;
    if (equirect) out.eyeCount = 1;  // the CLI refuses stereo equirect; never two 360° eyes here
    out.eyeWidth = std::max(1u, width / out.eyeCount);
    out.yfov = equirect ? 3.14159265f : std::clamp(camera.yfov, 1e-3f, 3.1f);
    out.jitter = rig.jitter ? halton23(frameIndex % 16) - glm::vec2(0.5f) : glm::vec2(0.0f);

    const glm::mat4 centre = safeLookAt(camera.position, camera.target, camera.up);
    const float aspect = float(out.eyeWidth) / float(out.height);  // both >= 1
    // Equirect has no projection matrix: viewProj = view (see CameraRigOptions::model).
    const glm::mat4 proj =
        equirect ? glm::mat4(1.0f)
                 : glm::perspectiveRH_ZO(out.yfov, aspect, std::max(camera.znear, 1e-6f), 1e6f);
    for (uint32_t e = 0; e < out.eyeCount; ++e) {
        EyeView& eye = out.eyes[e];
        // Parallel stereo: each eye is shifted along the camera's right axis by half the IPD.
        const float shift = out.eyeCount == 2 ? (e == 0 ? 0.5f : -0.5f) * rig.ipd : 0.0f;
        eye.view = glm::translate(glm::mat4(1.0f), glm::vec3(shift, 0.0f, 0.0f)) * centre;
        eye.proj = proj;
        eye.viewProj = proj * eye.view;
        eye.invViewProj = glm::inverse(eye.viewProj);
        eye.position = glm::vec3(glm::inverse(eye.view)[3]);
        eye.gaze = gaze ? glm::clamp(gaze[e], glm::vec2(0.0f), glm::vec2(1.0f)) : glm::vec2(0.5f);
        eye.offsetX = e * out.eyeWidth;
        const bool samePrevious =
            previous && previous->eyeCount == out.eyeCount && previous->model == out.model;
        eye.prevViewProj = samePrevious ? previous->eyes[e].viewProj : eye.viewProj;
        eye.prevGaze =
            previous && previous->eyeCount == out.eyeCount ? previous->eyes[e].gaze : eye.gaze;
    }
    return out;
}

void primaryRay(const FrameCamera& camera, glm::vec2 pixel, glm::vec3& origin, glm::vec3& dir) {
    // cameraEyeOf + cameraRay of camera.glsl; CameraGpu.cpp packs the same quantities.
    const uint32_t eyeWidth = std::max(camera.eyeWidth, 1u);
    const uint32_t column = pixel.x > 0.0f ? uint32_t(pixel.x) : 0u;
    const uint32_t e = std::min(column / eyeWidth, std::max(camera.eyeCount, 1u) - 1u);
    const EyeView& eye = camera.eyes[e];
    const glm::mat4 cameraToWorld = glm::inverse(eye.view);
    const glm::vec2 local = pixel - glm::vec2(float(eye.offsetX), 0.0f);
    const glm::vec2 size(float(eyeWidth), float(std::max(camera.height, 1u)));
    origin = eye.position;
    if (camera.model == CameraModel::Equirect) {
        dir = glm::normalize(glm::mat3(cameraToWorld) * equirectDirection(local / size));
        return;
    }
    const glm::vec2 ndc(2.0f * local.x / size.x - 1.0f, 1.0f - 2.0f * local.y / size.y);
    const float t = std::tan(0.5f * camera.yfov);
    const float aspect = size.x / size.y;
    const glm::vec3 d(ndc.x * t * aspect, ndc.y * t, -1.0f);
    dir = glm::normalize(glm::mat3(cameraToWorld) * d);  // |d| >= 1 (z = -1)
}

}  // namespace fovea::scene
