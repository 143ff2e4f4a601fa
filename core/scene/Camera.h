// Per-frame camera state handed to passes: one view per eye (mono = 1 eye, stereo = 2 eyes side
// by side in one image, seed 000 §3.1), current and previous matrices for reprojection, the
// sub-pixel jitter of this frame (Halton 2,3 for TAA), the gaze point of each eye and the camera
// cut flag that invalidates history.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>

#include "core/scene/Scene.h"

namespace fovea::scene {

constexpr uint32_t kMaxEyes = 2;

// How pixels map to ray directions. Perspective: a pinhole with vertical FOV `yfov`.
// Equirect: the whole sphere of directions around the eye in a 2:1 latitude-longitude image
// (seed 003 P4 §3: 360° content is rendered "as equirectangular images"); u = 0.5 looks at the
// camera's target, v = 0 is straight up. See docs/camera-path.md "Camera models".
enum class CameraModel : uint32_t { Perspective = 0, Equirect = 1 };

// "perspective" / "equirect"; parseCameraModel returns nullopt for anything else.
const char* cameraModelName(CameraModel model);
std::optional<CameraModel> parseCameraModel(const std::string& name);

// The unit direction, in the camera's frame (-Z forward, +Y up, +X right), of the point `uv` in
// [0,1]^2 of an equirect image: longitude (u - 0.5) * 2π, latitude (0.5 - v) * π. Same formula as
// cameraRay in shaders/common/camera.glsl.
glm::vec3 equirectDirection(glm::vec2 uv);
// The inverse: uv in [0,1]^2 of a camera-frame direction (any length > 0; the zero vector maps to
// the image centre).
glm::vec2 equirectUv(glm::vec3 direction);

struct EyeView {
    glm::mat4 view{1.0f}, proj{1.0f};
    glm::mat4 viewProj{1.0f}, invViewProj{1.0f};
    glm::mat4 prevViewProj{1.0f};  // the previous frame's (jitter-free) matrix, for motion vectors
    glm::vec3 position{0.0f};      // eye position in world space
    glm::vec2 gaze{0.5f};          // gaze point in [0,1]^2 of this eye's image (0,0 = top-left)
    glm::vec2 prevGaze{0.5f};      // the previous frame's gaze (VP reprojection, P5 §3.3)
    uint32_t offsetX = 0;          // first column of this eye in the side-by-side image
};

struct FrameCamera {
    EyeView eyes[kMaxEyes];
    uint32_t eyeCount = 1;
    uint32_t eyeWidth = 0, height = 0;  // per-eye image size in pixels
    glm::vec2 jitter{0.0f};             // sub-pixel offset in pixels, in [-0.5, 0.5)^2
    bool cut = false;                   // history must not be reused this frame
    float yfov = 0.8f;                  // perspective only (equirect: π, its vertical extent)
    CameraModel model = CameraModel::Perspective;
};

// Stereo and jitter options of a run.
struct CameraRigOptions {
    bool stereo = false;
    float ipd = 0.064f;  // interpupillary distance in scene units (metres for most glTF files)
    bool jitter = false;
    // Equirect: one eye (stereo is refused by the CLI); viewProj is the view matrix alone, so
    // prevViewProj * p is the previous camera-frame position (camera.glsl's
    // cameraPreviousPixel maps it back to the sphere).
    CameraModel model = CameraModel::Perspective;
};

// How a side-by-side image `width` pixels wide splits into eyes, for passes that keep their taps
// inside an eye: `eyesParam` > 0 forces a count, 0 takes the camera's (1..kMaxEyes); an image
// narrower than its eye count is one eye. eyeWidth >= 1; the last eye takes the remainder.
struct EyeSplit {
    int eyes = 1;
    int eyeWidth = 1;
};
EyeSplit splitEyes(uint32_t width, int eyesParam, uint32_t cameraEyes);

// Halton (2,3) point `index` (1-based internally) in [0,1)^2.
glm::vec2 halton23(uint64_t index);

// Builds the per-eye matrices for `camera` at a render size of `width` x `height` (the whole
// side-by-side image when stereo). `previous` supplies prevViewProj (null: same as this frame).
// `frameIndex` selects the jitter sample. `gaze` holds one gaze point per eye.
FrameCamera makeFrameCamera(const CameraDesc& camera, uint32_t width, uint32_t height,
                            const CameraRigOptions& rig, uint64_t frameIndex,
                            const FrameCamera* previous, const glm::vec2 gaze[kMaxEyes]);

// The primary ray through `pixel` (coordinates of the whole side-by-side image, e.g.
// (x, y) + 0.5 + jitter), built exactly like cameraRay in shaders/common/camera.glsl for the eye
// that covers column floor(pixel.x): CPU references of the ray-cast passes use it.
void primaryRay(const FrameCamera& camera, glm::vec2 pixel, glm::vec3& origin, glm::vec3& dir);

}  // namespace fovea::scene
