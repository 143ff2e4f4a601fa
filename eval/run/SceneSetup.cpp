#include "eval/run/SceneSetup.h"

#include <chrono>
#include <filesystem>
#include <sstream>

#include "core/graph/Pass.h"
#include "core/scene/Environment.h"
#include "core/scene/LightTable.h"
#include "core/scene/SceneGpu.h"
#include "core/scene/SceneLoader.h"
#include "core/scene/ViewProbe.h"
#include "core/util/Error.h"

namespace fovea::eval {

namespace fs = std::filesystem;

namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// A path from the graph's defaults is relative to the graph file; one from the command line is
// relative to the working directory.
std::string relativeToGraph(const std::string& path, const graph::GraphDesc& desc) {
    if (path == "none" || path.rfind("builtin:", 0) == 0 || fs::path(path).is_absolute() ||
        desc.file.empty())
        return path;
    return (fs::path(desc.file).parent_path() / path).lexically_normal().string();
}

scene::CameraDesc gltfCamera(const scene::Scene& s, const std::string& which) {
    if (s.cameras.empty())
        throw InputError("--camera", "", "'gltf:" + which + "': the scene has no cameras");
    char* end = nullptr;
    unsigned long index = std::strtoul(which.c_str(), &end, 10);
    if (!which.empty() && *end == '\0') {
        if (index >= s.cameras.size())
            throw InputError("--camera", "",
                             "'gltf:" + which + "': the scene has " +
                                 std::to_string(s.cameras.size()) + " camera(s)");
        return s.cameras[index];
    }
    std::string names;
    for (const auto& c : s.cameras) {
        if (c.name == which) return c;
        names += (names.empty() ? "'" : ", '") + c.name + "'";
    }
    throw InputError("--camera", "",
                     "'gltf:" + which + "': no camera of that name (cameras: " + names + ")");
}

}  // namespace

nlohmann::json environmentKey(const SceneOptions& o) {
    if (o.env.empty()) return nullptr;
    nlohmann::json j = {
        {"file", o.env}, {"intensity", o.envIntensity}, {"rotation_degrees", o.envRotation}};
    std::error_code ec;
    const auto bytes = fs::file_size(o.env, ec);
    if (!ec) j["bytes"] = bytes;
    const auto written = fs::last_write_time(o.env, ec);
    if (!ec) j["modified"] = int64_t(written.time_since_epoch().count());
    return j;
}

nlohmann::json sceneOptionsKey(const SceneOptions& o) {
    auto file = [](const std::string& path) {
        std::error_code ec;
        const auto bytes = fs::is_regular_file(path, ec) ? fs::file_size(path, ec) : 0;
        return nlohmann::json{{"path", path}, {"bytes", ec ? 0 : bytes}};
    };
    return {{"scene", file(o.scene)},
            {"camera", file(o.camera)},
            {"stereo", o.stereo},
            {"mono", o.mono},
            {"camera_model", o.cameraModel},
            {"ipd", o.ipd},
            {"gaze", o.gaze},
            {"jitter", o.jitter},
            {"sun", o.sun},
            {"env", environmentKey(o)}};
}

std::array<glm::vec2, scene::kMaxEyes> parseGaze(const std::string& text) {
    std::vector<float> v;
    std::stringstream s(text);
    std::string item;
    while (std::getline(s, item, ',')) {
        char* end = nullptr;
        float f = std::strtof(item.c_str(), &end);
        if (item.empty() || *end != '\0' || !(f >= 0.0f && f <= 1.0f))
            throw InputError("--gaze", "",
                             "expected numbers in [0,1] as x,y or xl,yl,xr,yr, got '" + text + "'");
        v.push_back(f);
    }
    if (!text.empty() && text.back() == ',') v.clear();  // a trailing comma is a typo, not a list
    if (v.size() == 2) return {glm::vec2(v[0], v[1]), glm::vec2(v[0], v[1])};
    if (v.size() == 4) return {glm::vec2(v[0], v[1]), glm::vec2(v[2], v[3])};
    throw InputError("--gaze", "", "expected x,y or xl,yl,xr,yr in [0,1], got '" + text + "'");
}

RunScene::RunScene(const SceneOptions& o, const graph::GraphDesc& desc) {
    if (o.stereo && o.mono)
        throw InputError("--stereo", "", "--stereo and --mono exclude each other");
    std::string spec =
        !o.scene.empty() ? o.scene : relativeToGraph(desc.defaults.scene.value_or("none"), desc);
    mRig.stereo = o.stereo || (!o.mono && desc.defaults.stereo.value_or(false));
    mRig.ipd = o.ipd;
    mRig.jitter = o.jitter;
    if (!o.gaze.empty()) mGaze = parseGaze(o.gaze);
    if (desc.defaults.cameraModel)
        mRig.model = *scene::parseCameraModel(*desc.defaults.cameraModel);  // checked by the parser
    // The graph's defaults.camera was made for its default scene: with another --scene it would
    // look at nothing (an all-black image), so it is dropped with a warning.
    const std::string defaultScene = relativeToGraph(desc.defaults.scene.value_or("none"), desc);
    const bool sceneOverridden = !o.scene.empty() && spec != defaultScene;
    const bool graphCamera = o.camera.empty() && desc.defaults.camera && !o.ignoreGraphCamera;
    std::string droppedCamera;
    if (graphCamera && sceneOverridden) droppedCamera = *desc.defaults.camera;
    std::string camera = !o.camera.empty() ? o.camera
                         : graphCamera && droppedCamera.empty()
                             ? relativeToGraph(*desc.defaults.camera, desc)
                             : std::string();
    if (spec == "none") {
        if (!o.camera.empty()) throw InputError("--camera", "", "a camera needs a scene (--scene)");
        return;
    }
    auto t0 = std::chrono::steady_clock::now();
    try {
        mScene = std::make_unique<scene::Scene>(scene::loadScene(spec, o.allowExternalUris));
    } catch (const InputError& e) {
        if (!o.scene.empty()) throw InputError("--scene", "", e.what());
        throw InputError(desc.file, "/defaults/scene", e.what());
    }
    mLoadMs = msSince(t0);
    mSpec = spec;
    if (o.sun) {
        scene::Light sun;
        sun.type = scene::Light::Type::Directional;
        sun.name = "--sun";
        sun.direction =
            glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));  // non-zero: normalize is safe
        sun.intensity = 3.0f;
        mScene->lights.push_back(sun);
    }
    if (!o.env.empty()) {
        if (o.env.rfind("builtin:", 0) == 0)
            throw InputError("--env", "", "expected an image file, got '" + o.env + "'");
        mScene->environment = std::make_shared<scene::EnvironmentMap>(
            scene::loadEnvironment(o.env, o.envIntensity, o.envRotation, mScene->warnings));
        mEnvironment = environmentKey(o);
        mEnvironment["size"] = {mScene->environment->width, mScene->environment->height};
    } else if (o.envIntensity != 1.0f || o.envRotation != 0.0f) {
        throw InputError(o.envIntensity != 1.0f ? "--env-intensity" : "--env-rotation", "",
                         "has no effect without --env");
    }
    if (!(mScene->features() &
          (graph::kSceneEmissive | graph::kScenePunctual | graph::kSceneEnvironment)))
        mScene->warnings.push_back(
            "the scene has no light (no emissive material, no "
            "KHR_lights_punctual light, no --env): path-traced images will be black; "
            "--sun adds a directional light, --env an environment");
    if (!droppedCamera.empty())
        mScene->warnings.push_back("the graph's defaults.camera '" + droppedCamera +
                                   "' belongs to its default scene '" + defaultScene +
                                   "' and is not used with --scene " + spec +
                                   " (pass --camera to choose one; --camera frame frames the "
                                   "scene)");
    if (camera == kFrameCamera) {
        mPath = scene::CameraPath::still(mScene->defaultCamera());
        mCameraSource = "default";
    } else if (camera.rfind("gltf:", 0) == 0) {
        mPath = scene::CameraPath::still(gltfCamera(*mScene, camera.substr(5)));
        mCameraSource = camera;
    } else if (!camera.empty()) {
        try {
            mPath = scene::CameraPath::load(camera);
        } catch (const InputError& e) {
            // Reached through the graph: say which graph field named the file.
            if (o.camera.empty()) throw InputError(desc.file, "/defaults/camera", e.what());
            throw;
        }
        mCameraSource = "path:" + camera;
    } else if (!mScene->cameras.empty()) {
        mPath = scene::CameraPath::still(mScene->cameras.front());
        mCameraSource = "gltf:0";
    } else {
        mPath = scene::CameraPath::still(mScene->defaultCamera());
        mCameraSource = "default";
    }
    if (mPath && mPath->model()) mRig.model = *mPath->model();
    if (!o.cameraModel.empty()) mRig.model = *scene::parseCameraModel(o.cameraModel);
    if (mRig.model == scene::CameraModel::Equirect && mRig.stereo)
        throw InputError(o.stereo ? "--stereo" : desc.file, o.stereo ? "" : "/defaults/stereo",
                         "an equirect (360°) camera renders one eye; stereo equirect "
                         "(top-bottom) is not supported (use --mono)");
}

RunScene::~RunScene() = default;

void RunScene::checkRenderSize(uint32_t width, uint32_t height) const {
    if (mRig.model == scene::CameraModel::Equirect && uint64_t(width) != 2 * uint64_t(height))
        throw InputError("--size", "",
                         "an equirect camera covers 360° x 180° in a 2:1 image: the width must "
                         "be twice the height, got " +
                             std::to_string(width) + "x" + std::to_string(height));
    if (mRig.stereo && width < 2)
        throw InputError("--size", "",
                         "stereo renders two eyes of width/2 side by side: the width must be at "
                         "least 2, got " +
                             std::to_string(width));
}

uint32_t RunScene::features() const {
    if (!mScene) return 0;
    return mScene->features() | (mRig.stereo ? graph::kSceneStereo : 0u) |
           (mRig.model == scene::CameraModel::Equirect ? graph::kSceneEquirect : 0u);
}

void RunScene::upload(gpu::Context& context) {
    if (!mScene) return;
    auto t0 = std::chrono::steady_clock::now();
    mBvh = std::make_unique<scene::Bvh>(mScene->mesh);
    const scene::LightTable lights(*mScene, mBvh->triangleOrder());
    mGpu = std::make_unique<scene::SceneGpu>(context, *mScene, *mBvh, lights);
    mUploadMs = msSince(t0);
}

std::optional<scene::ViewProbe> RunScene::probeView(const scene::FrameCamera& camera) const {
    if (!mScene || !mBvh) return std::nullopt;
    return scene::probeView(*mScene, *mBvh, camera);
}

scene::CameraDesc RunScene::cameraAt(uint64_t frame) const {
    return mPath ? mPath->at(frame).camera : scene::CameraDesc{};
}

scene::FrameCamera RunScene::frameCamera(uint64_t frame, uint32_t width, uint32_t height,
                                         const scene::CameraDesc* pose) {
    scene::CameraSample sample =
        mPath ? mPath->at(frame) : scene::CameraSample{scene::CameraDesc{}, std::nullopt, false};
    if (pose) {  // steered by the user: no cut from the path
        sample.camera = *pose;
        sample.cut = false;
    }
    std::array<glm::vec2, scene::kMaxEyes> gaze = sample.gaze.value_or(mGaze);
    const scene::FrameCamera* previous = mPrevious && !sample.cut ? &*mPrevious : nullptr;
    scene::FrameCamera camera =
        scene::makeFrameCamera(sample.camera, width, height, mRig, frame, previous, gaze.data());
    camera.cut = sample.cut && frame > 0;
    mPrevious = camera;
    return camera;
}

nlohmann::json RunScene::json() const {
    if (!mScene) return "none";
    nlohmann::json j = {{"spec", mSpec},
                        {"triangles", mScene->mesh.triangles.size()},
                        {"materials", mScene->materials.size()},
                        {"lights", mScene->lights.size()},
                        {"features", graph::sceneFeatureNames(features())},
                        {"camera", mCameraSource},
                        {"stereo", mRig.stereo},
                        {"camera_model", scene::cameraModelName(mRig.model)},
                        {"load_ms", mLoadMs},
                        {"warnings", mScene->warnings}};
    if (!mEnvironment.is_null()) j["environment"] = mEnvironment;
    if (mGpu) {
        const auto& bvh = mGpu->bvhStats();
        j["upload_ms"] = mUploadMs;  // BVH build + light table + upload
        j["gpu_bytes"] = mGpu->totalBytes();
        j["bvh"] = {{"nodes", bvh.nodeCount},
                    {"leaves", bvh.leafCount},
                    {"max_depth", bvh.maxDepth},
                    {"sah_cost", bvh.sahCost},
                    {"build_ms", bvh.buildMs},
                    {"invalid_triangles", bvh.invalidTriangles},
                    {"emissive_triangles", mGpu->info().emissiveTriangleCount}};
    }
    return j;
}

}  // namespace fovea::eval
