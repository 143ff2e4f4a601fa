// Cameras, stereo rig, jitter sequence and camera paths (CPU only).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/scene/Camera.h"
#include "core/scene/CameraPath.h"
#include "core/util/Error.h"

using namespace fovea;
using namespace fovea::scene;
using nlohmann::json;

namespace {

CameraDesc lookingDownMinusZ() {
    CameraDesc c;
    c.position = {0, 1, 5};
    c.target = {0, 1, 0};
    c.yfov = 0.8f;
    return c;
}

glm::vec3 project(const glm::mat4& viewProj, const glm::vec3& p) {
    glm::vec4 clip = viewProj * glm::vec4(p, 1.0f);
    return glm::vec3(clip) / clip.w;
}

std::string pathError(const json& j) {
    try {
        CameraPath::fromJson(j, "cam.json");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Camera, HaltonSequenceStartsOffCentre) {
    EXPECT_FLOAT_EQ(halton23(0).x, 0.5f);
    EXPECT_FLOAT_EQ(halton23(0).y, 1.0f / 3.0f);
    EXPECT_FLOAT_EQ(halton23(1).x, 0.25f);
    EXPECT_FLOAT_EQ(halton23(1).y, 2.0f / 3.0f);
    // 16 samples cover the pixel: mean close to the centre.
    glm::vec2 mean(0.0f);
    for (uint64_t i = 0; i < 16; ++i) mean += halton23(i) / 16.0f;
    EXPECT_NEAR(mean.x, 0.5f, 0.04f);
    EXPECT_NEAR(mean.y, 0.5f, 0.04f);
}

TEST(Camera, TargetProjectsToImageCentre) {
    FrameCamera cam = makeFrameCamera(lookingDownMinusZ(), 64, 32, {}, 0, nullptr, nullptr);
    ASSERT_EQ(cam.eyeCount, 1u);
    EXPECT_EQ(cam.eyeWidth, 64u);
    glm::vec3 ndc = project(cam.eyes[0].viewProj, {0, 1, 0});
    EXPECT_NEAR(ndc.x, 0.0f, 1e-5f);
    EXPECT_NEAR(ndc.y, 0.0f, 1e-5f);
    EXPECT_GT(ndc.z, 0.0f);
    EXPECT_LT(ndc.z, 1.0f);
    // A point at the top edge of the vertical FOV lands on |ndc.y| = 1.
    glm::vec3 top = project(cam.eyes[0].viewProj, {0, 1 + 5 * std::tan(0.4f), 0});
    EXPECT_NEAR(std::abs(top.y), 1.0f, 1e-4f);
    EXPECT_NEAR(cam.eyes[0].position.z, 5.0f, 1e-5f);
    EXPECT_EQ(cam.jitter, glm::vec2(0.0f));
}

TEST(Camera, StereoEyesAreSeparatedByIpdSideBySide) {
    CameraRigOptions rig;
    rig.stereo = true;
    rig.ipd = 0.1f;
    FrameCamera cam = makeFrameCamera(lookingDownMinusZ(), 128, 64, rig, 0, nullptr, nullptr);
    ASSERT_EQ(cam.eyeCount, 2u);
    EXPECT_EQ(cam.eyeWidth, 64u);
    EXPECT_EQ(cam.eyes[0].offsetX, 0u);
    EXPECT_EQ(cam.eyes[1].offsetX, 64u);
    // Eye 0 is the left eye (camera right is +x here).
    EXPECT_NEAR(cam.eyes[0].position.x, -0.05f, 1e-5f);
    EXPECT_NEAR(cam.eyes[1].position.x, 0.05f, 1e-5f);
    EXPECT_NEAR(glm::distance(cam.eyes[0].position, cam.eyes[1].position), 0.1f, 1e-5f);
    // Parallel rig: a far point projects to (almost) the same place in both eyes.
    glm::vec3 far0 = project(cam.eyes[0].viewProj, {0, 1, -1e4f});
    glm::vec3 far1 = project(cam.eyes[1].viewProj, {0, 1, -1e4f});
    EXPECT_NEAR(far0.x, far1.x, 1e-4f);
}

TEST(Camera, PreviousMatricesAndJitter) {
    CameraRigOptions rig;
    rig.jitter = true;
    FrameCamera first = makeFrameCamera(lookingDownMinusZ(), 32, 32, rig, 0, nullptr, nullptr);
    EXPECT_EQ(first.eyes[0].prevViewProj, first.eyes[0].viewProj);
    CameraDesc moved = lookingDownMinusZ();
    moved.position.x += 1.0f;
    FrameCamera second = makeFrameCamera(moved, 32, 32, rig, 1, &first, nullptr);
    EXPECT_EQ(second.eyes[0].prevViewProj, first.eyes[0].viewProj);
    EXPECT_NE(second.eyes[0].viewProj, first.eyes[0].viewProj);
    EXPECT_NE(first.jitter, second.jitter);
    for (uint64_t f = 0; f < 32; ++f) {
        glm::vec2 j = makeFrameCamera(moved, 32, 32, rig, f, nullptr, nullptr).jitter;
        EXPECT_GE(j.x, -0.5f);
        EXPECT_LT(j.x, 0.5f);
        EXPECT_GE(j.y, -0.5f);
        EXPECT_LT(j.y, 0.5f);
    }
}

TEST(Camera, DegenerateUpAndTargetStayFinite) {
    CameraDesc c;
    c.position = {0, 5, 0};
    c.target = {0, 0, 0};
    c.up = {0, 1, 0};  // parallel to the view direction
    FrameCamera cam = makeFrameCamera(c, 16, 16, {}, 0, nullptr, nullptr);
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k) EXPECT_TRUE(std::isfinite(cam.eyes[0].invViewProj[i][k]));
    c.target = c.position;  // no view direction at all
    cam = makeFrameCamera(c, 16, 16, {}, 0, nullptr, nullptr);
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k) EXPECT_TRUE(std::isfinite(cam.eyes[0].viewProj[i][k]));
}

TEST(Camera, GazeIsPerEyeAndClamped) {
    CameraRigOptions rig;
    rig.stereo = true;
    const glm::vec2 gaze[2] = {{0.25f, 0.5f}, {1.5f, -1.0f}};
    FrameCamera cam = makeFrameCamera(lookingDownMinusZ(), 64, 32, rig, 0, nullptr, gaze);
    EXPECT_EQ(cam.eyes[0].gaze, glm::vec2(0.25f, 0.5f));
    EXPECT_EQ(cam.eyes[1].gaze, glm::vec2(1.0f, 0.0f));
}

TEST(CameraPath, InterpolatesBetweenKeys) {
    json j = {{"version", 1},
              {"keyframes",
               {{{"frame", 0}, {"position", {0, 0, 5}}, {"target", {0, 0, 0}}, {"yfov_deg", 40}},
                {{"frame", 10}, {"position", {10, 0, 5}}, {"yfov_deg", 60}}}}};
    CameraPath path = CameraPath::fromJson(j, "cam.json");
    EXPECT_EQ(path.length(), 11u);
    EXPECT_EQ(path.at(0).camera.position, glm::vec3(0, 0, 5));
    EXPECT_EQ(path.at(10).camera.position, glm::vec3(10, 0, 5));
    EXPECT_NEAR(path.at(5).camera.position.x, 5.0f, 1e-5f);
    EXPECT_NEAR(path.at(5).camera.yfov, 50.0f * 3.14159265f / 180.0f, 1e-5f);
    // The target is inherited from the previous key.
    EXPECT_EQ(path.at(10).camera.target, glm::vec3(0, 0, 0));
    // Past the end the last key holds (no loop).
    EXPECT_EQ(path.at(100).camera.position, glm::vec3(10, 0, 5));
    EXPECT_FALSE(path.at(100).cut);
}

TEST(CameraPath, LoopWrapsAndMarksTheJumpAsCut) {
    json j = {{"version", 1},
              {"loop", true},
              {"keyframes",
               {{{"frame", 0}, {"position", {0, 0, 5}}, {"target", {0, 0, 0}}},
                {{"frame", 4}, {"position", {4, 0, 5}}}}}};
    CameraPath path = CameraPath::fromJson(j, "cam.json");
    EXPECT_NEAR(path.at(7).camera.position.x, path.at(2).camera.position.x, 1e-6f);
    EXPECT_FALSE(path.at(0).cut);
    EXPECT_TRUE(path.at(5).cut);  // frame 5 wraps to frame 0
    EXPECT_FALSE(path.at(6).cut);
}

TEST(CameraPath, CutHoldsUntilTheCutFrame) {
    json j = {{"version", 1},
              {"keyframes",
               {{{"frame", 0}, {"position", {0, 0, 5}}, {"target", {0, 0, 0}}},
                {{"frame", 4}, {"position", {100, 0, 5}}, {"cut", true}},
                {{"frame", 8}, {"position", {104, 0, 5}}}}}};
    CameraPath path = CameraPath::fromJson(j, "cam.json");
    EXPECT_EQ(path.at(3).camera.position, glm::vec3(0, 0, 5));
    EXPECT_FALSE(path.at(3).cut);
    EXPECT_TRUE(path.at(4).cut);
    EXPECT_EQ(path.at(4).camera.position, glm::vec3(100, 0, 5));
    // The spline after the cut does not use the key before it.
    EXPECT_NEAR(path.at(6).camera.position.x, 102.0f, 1e-4f);
}

TEST(CameraPath, GazeFromKeys) {
    json j = {{"version", 1},
              {"keyframes",
               {{{"frame", 0},
                 {"position", {0, 0, 5}},
                 {"target", {0, 0, 0}},
                 {"gaze", {{0.2, 0.5}, {0.4, 0.5}}}},
                {{"frame", 2}, {"position", {0, 0, 6}}, {"gaze", {{0.6, 0.5}}}}}}};
    CameraPath path = CameraPath::fromJson(j, "cam.json");
    ASSERT_TRUE(path.at(1).gaze.has_value());
    EXPECT_NEAR((*path.at(1).gaze)[0].x, 0.4f, 1e-6f);
    EXPECT_NEAR((*path.at(1).gaze)[1].x, 0.5f, 1e-6f);
}

TEST(CameraPath, ErrorsNameFileAndPointer) {
    auto key = [](int frame) {
        return json{{"frame", frame}, {"position", {0, 0, 5}}, {"target", {0, 0, 0}}};
    };
    EXPECT_NE(pathError({{"version", 2}, {"keyframes", {key(0)}}}).find("cam.json: /version"),
              std::string::npos);
    EXPECT_NE(pathError({{"version", 1}, {"keyframes", json::array()}}).find("/keyframes"),
              std::string::npos);
    std::string msg = pathError({{"version", 1}, {"keyframes", {key(3), key(3)}}});
    EXPECT_NE(msg.find("cam.json: /keyframes/1/frame"), std::string::npos) << msg;
    json typo = key(0);
    typo["positon"] = {0, 0, 1};
    msg = pathError({{"version", 1}, {"keyframes", {typo}}});
    EXPECT_NE(msg.find("positon"), std::string::npos) << msg;
    EXPECT_NE(msg.find("position"), std::string::npos) << msg;
    json badFov = key(0);
    badFov["yfov_deg"] = 0;
    msg = pathError({{"version", 1}, {"keyframes", {badFov}}});
    EXPECT_NE(msg.find("/keyframes/0/yfov_deg"), std::string::npos) << msg;
    json same = key(0);
    same["target"] = {0, 0, 5};
    EXPECT_NE(pathError({{"version", 1}, {"keyframes", {same}}}).find("coincide"),
              std::string::npos);
    json gaze = key(0);
    gaze["gaze"] = {{1.5, 0.5}};
    msg = pathError({{"version", 1}, {"keyframes", {gaze}}});
    EXPECT_NE(msg.find("/keyframes/0/gaze/0/0"), std::string::npos) << msg;
    EXPECT_THROW(CameraPath::load("/nonexistent/cam.json"), InputError);
}

TEST(CameraPath, ShippedPathsLoad) {
    const std::filesystem::path dir =
        std::filesystem::path(FOVEA_TEST_DIR).parent_path() / "graphs" / "cameras";
    size_t count = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        if (e.path().extension() != ".json") continue;
        CameraPath path = CameraPath::load(e.path());
        EXPECT_GE(path.keys().size(), 1u) << e.path();
        ++count;
    }
    EXPECT_GE(count, 1u);
    // The Cornell dolly has its cut at frame 8: the camera jumps there and nowhere else.
    CameraPath dolly = CameraPath::load(dir / "cornell_dolly.json");
    for (uint64_t f = 0; f < 16; ++f) EXPECT_EQ(dolly.at(f).cut, f == 8) << "frame " << f;
}
