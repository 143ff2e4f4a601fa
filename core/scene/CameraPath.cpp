#include "core/scene/CameraPath.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/util/Error.h"
#include "core/util/JsonUtil.h"
#include "core/util/UserFile.h"

namespace fovea::scene {
namespace {

constexpr int kCameraPathVersion = 1;
constexpr float kPi = 3.14159265358979f;

glm::vec3 readVec3(const JsonNode& node) {
    if (node.size() != 3) node.fail("expected an array of 3 numbers");
    glm::vec3 v;
    for (size_t i = 0; i < 3; ++i) {
        double d = node.at(i).asNumber();
        if (!std::isfinite(d) || std::abs(d) > 1e30) node.at(i).fail("expected a finite number");
        v[int(i)] = float(d);
    }
    return v;
}

glm::vec2 readGaze(const JsonNode& node) {
    if (node.size() != 2) node.fail("expected [x, y] in [0, 1]");
    glm::vec2 g;
    for (size_t i = 0; i < 2; ++i) {
        double d = node.at(i).asNumber();
        if (!(d >= 0.0 && d <= 1.0)) node.at(i).fail("out of range (allowed 0..1)");
        g[int(i)] = float(d);
    }
    return g;
}

// Catmull-Rom through p1..p2 with neighbours p0, p3 (uniform parameterization).
glm::vec3 catmullRom(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                     const glm::vec3& p3, float t) {
    float t2 = t * t, t3 = t2 * t;
    return 0.5f * (2.0f * p1 + (-p0 + p2) * t + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * t2 +
                   (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * t3);
}

}  // namespace

CameraPath CameraPath::still(const CameraDesc& camera) {
    CameraPath path;
    path.mKeys.push_back({0, camera, std::nullopt, false});
    return path;
}

CameraPath CameraPath::fromJson(const nlohmann::json& j, const std::string& file) {
    JsonNode root(j, file);
    root.expectObject().checkFields(
        {"version", "description", "loop", "camera_model", "keyframes"});
    int64_t version = root.require("version").asInt();
    if (version != kCameraPathVersion)
        root.require("version").fail("unsupported camera path version " + std::to_string(version) +
                                     " (this fovea reads version " +
                                     std::to_string(kCameraPathVersion) + ")");
    CameraPath path;
    if (auto loop = root.find("loop")) path.mLoop = loop->asBool();
    if (auto model = root.find("camera_model")) {
        path.mModel = parseCameraModel(model->asString());
        if (!path.mModel) model->fail("expected \"perspective\" or \"equirect\"");
    }
    JsonNode keys = root.require("keyframes");
    if (keys.size() == 0) keys.fail("a camera path needs at least one keyframe");
    for (const JsonNode& k : keys.elements()) {
        k.expectObject().checkFields(
            {"frame", "position", "target", "up", "yfov_deg", "gaze", "cut", "znear"});
        CameraKey key;
        key.frame = uint64_t(k.require("frame").asInt(0, int64_t(1) << 40));
        if (!path.mKeys.empty() && key.frame <= path.mKeys.back().frame)
            k.require("frame").fail("keyframes must have strictly increasing frames (previous " +
                                    std::to_string(path.mKeys.back().frame) + ")");
        // Unset fields inherit the previous key, so a path can move only the position.
        if (!path.mKeys.empty()) key.camera = path.mKeys.back().camera;
        key.camera.position = readVec3(k.require("position"));
        if (auto t = k.find("target"))
            key.camera.target = readVec3(*t);
        else if (path.mKeys.empty())
            k.fail("missing required field 'target' (first keyframe)");
        if (auto u = k.find("up")) key.camera.up = readVec3(*u);
        if (auto f = k.find("yfov_deg")) {
            double deg = f->asNumber();
            if (!(deg > 0.5 && deg < 179.0)) f->fail("out of range (allowed 0.5..179 degrees)");
            key.camera.yfov = float(deg) * kPi / 180.0f;
        }
        if (auto n = k.find("znear")) {
            double z = n->asNumber();
            if (!(z > 0.0 && z < 1e6)) n->fail("expected a positive near plane distance");
            key.camera.znear = float(z);
        }
        if (glm::length(key.camera.target - key.camera.position) < 1e-12f)
            k.fail("position and target coincide: the view direction is undefined");
        if (auto g = k.find("gaze")) {
            if (g->size() < 1 || g->size() > kMaxEyes)
                g->fail("expected one [x, y] per eye (1 or 2)");
            std::array<glm::vec2, kMaxEyes> gaze{};
            for (size_t e = 0; e < kMaxEyes; ++e)
                gaze[e] = readGaze(g->at(std::min(e, g->size() - 1)));
            key.gaze = gaze;
        }
        if (auto c = k.find("cut")) key.cut = c->asBool();
        path.mKeys.push_back(std::move(key));
    }
    return path;
}

CameraPath CameraPath::load(const std::filesystem::path& path) {
    const std::string text = readUserTextFile(path, kMaxJsonFileBytes, "camera path file");
    return fromJson(parseJsonText(text, path.string()), path.string());
}

uint64_t CameraPath::length() const {
    return mKeys.back().frame - mKeys.front().frame + 1;
}

CameraSample CameraPath::at(uint64_t frame) const {
    const uint64_t first = mKeys.front().frame, last = mKeys.back().frame;
    uint64_t f = frame;
    bool wrapped = false;
    if (mLoop && mKeys.size() > 1 && f > last) {
        f = first + (f - first) % (last - first + 1);
        wrapped = true;
    }
    auto it = std::upper_bound(mKeys.begin(), mKeys.end(), f,
                               [](uint64_t v, const CameraKey& k) { return v < k.frame; });
    CameraSample sample;
    if (it == mKeys.begin() || it == mKeys.end()) {
        const CameraKey& key = it == mKeys.begin() ? mKeys.front() : mKeys.back();
        sample.camera = key.camera;
        sample.gaze = key.gaze;
        sample.cut = key.frame == f && key.cut;
    } else {
        const size_t i1 = size_t(it - mKeys.begin()) - 1, i2 = i1 + 1;
        const CameraKey& k1 = mKeys[i1];
        const CameraKey& k2 = mKeys[i2];
        if (k1.frame == f) {
            sample.camera = k1.camera;
            sample.gaze = k1.gaze;
            sample.cut = k1.cut;
        } else if (k2.cut) {
            // A cut at k2: hold k1 until the cut instead of sliding into the next shot.
            sample.camera = k1.camera;
            sample.gaze = k1.gaze;
        } else {
            // Frames differ (strictly increasing keys), so the division is safe.
            const float t = float(f - k1.frame) / float(k2.frame - k1.frame);
            const glm::vec3 p0 =
                i1 > 0 && !k1.cut ? mKeys[i1 - 1].camera.position : k1.camera.position;
            const glm::vec3 p3 = i2 + 1 < mKeys.size() && !mKeys[i2 + 1].cut
                                     ? mKeys[i2 + 1].camera.position
                                     : k2.camera.position;
            sample.camera = k1.camera;
            sample.camera.position = catmullRom(p0, k1.camera.position, k2.camera.position, p3, t);
            sample.camera.target = glm::mix(k1.camera.target, k2.camera.target, t);
            sample.camera.up = glm::mix(k1.camera.up, k2.camera.up, t);
            sample.camera.yfov = glm::mix(k1.camera.yfov, k2.camera.yfov, t);
            if (k1.gaze && k2.gaze) {
                std::array<glm::vec2, kMaxEyes> g;
                for (size_t e = 0; e < kMaxEyes; ++e)
                    g[e] = glm::mix((*k1.gaze)[e], (*k2.gaze)[e], t);
                sample.gaze = g;
            } else {
                sample.gaze = k1.gaze;
            }
        }
    }
    // Wrapping from the last key back to the first is a jump: treat it as a cut.
    if (wrapped && f == first) sample.cut = true;
    return sample;
}

}  // namespace fovea::scene
