// Camera paths for temporal runs: JSON keyframes (position, target, up, vertical FOV, optional
// gaze per eye, optional cut) interpolated per frame. Format in docs/camera-path.md:
//
//   { "version": 1, "loop": false,
//     "keyframes": [ { "frame": 0,  "position": [0,1,5], "target": [0,1,0], "yfov_deg": 45 },
//                    { "frame": 30, "position": [2,1,5], "target": [0,1,0], "cut": true } ] }
#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/Camera.h"

namespace fovea::scene {

struct CameraKey {
    uint64_t frame = 0;
    CameraDesc camera;
    std::optional<std::array<glm::vec2, kMaxEyes>> gaze;  // unset: keep the run's gaze
    bool cut = false;  // a camera cut happens at this key: no interpolation into it
};

struct CameraSample {
    CameraDesc camera;
    std::optional<std::array<glm::vec2, kMaxEyes>> gaze;
    bool cut = false;  // this frame starts a new shot (history invalid)
};

class CameraPath {
public:
    // A path holding one camera forever.
    static CameraPath still(const CameraDesc& camera);
    // Parses a path; errors name `file` and the JSON pointer.
    static CameraPath fromJson(const nlohmann::json& j, const std::string& file);
    static CameraPath load(const std::filesystem::path& path);

    // The camera of frame `frame`: positions follow a Catmull-Rom spline through the keys,
    // targets/up/FOV are interpolated linearly; before the first key the first key holds, after
    // the last key the last holds (or the path wraps when `loop`).
    CameraSample at(uint64_t frame) const;

    const std::vector<CameraKey>& keys() const { return mKeys; }
    bool loops() const { return mLoop; }
    // The path's "camera_model", if it names one (a run's --camera-model overrides it).
    std::optional<CameraModel> model() const { return mModel; }
    uint64_t length() const;  // frames from the first to the last key, + 1

private:
    std::vector<CameraKey> mKeys;  // sorted by frame, strictly increasing
    bool mLoop = false;
    std::optional<CameraModel> mModel;
};

}  // namespace fovea::scene
