// Free-fly camera of the inspector (WASD + mouse drag, or the script's `move`/`look`): a pose
// the user steers instead of the graph's camera path. Pure math, unit-tested without a window.
#pragma once
#include <glm/glm.hpp>

#include "core/scene/Scene.h"

namespace fovea::editor {

class FreeFlyCamera {
public:
    // Starts at `pose` (position, looking at target; the world's up is +Y, as in glTF).
    explicit FreeFlyCamera(const scene::CameraDesc& pose = {});

    // Moves by `local` = (right, up, forward) in scene units, along the view direction.
    void move(const glm::vec3& local);
    // Turns by yaw (positive: to the right) and pitch (positive: up) in degrees; the pitch is
    // kept inside (-89, 89) degrees so the view never flips over the pole.
    void look(float yawDegrees, float pitchDegrees);

    scene::CameraDesc pose() const;
    glm::vec3 position() const { return mPosition; }
    glm::vec3 forward() const;
    // Scene units per frame for a held key: 2% of the starting distance to the target, so a
    // scene of any scale crosses in about 50 frames.
    float step() const { return mStep; }

private:
    glm::vec3 mPosition{0.0f};
    float mYaw = 0.0f, mPitch = 0.0f;  // radians; yaw 0 looks down -Z
    float mFocus = 1.0f;               // distance of the target in front of the camera
    float mStep = 0.02f;
    scene::CameraDesc mBase;  // yfov, znear, name
};

}  // namespace fovea::editor
