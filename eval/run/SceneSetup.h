// What `run`, `reference` and `bench` share about scenes: the --scene/--camera/--stereo/--ipd/
// --gaze/--jitter options, loading the scene onto the GPU, and the camera of every frame (a path,
// a glTF camera or the default framing camera) handed to the graph before each frame.
#pragma once
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/graph/GraphDesc.h"
#include "core/scene/Camera.h"
#include "core/scene/CameraPath.h"
#include "core/scene/Scene.h"

namespace fovea::gpu {
class Context;
}
namespace fovea::scene {
class Bvh;
class SceneGpu;
struct ViewProbe;
}  // namespace fovea::scene

namespace fovea::eval {

struct SceneOptions {
    std::string scene;  // empty: the graph's defaults.scene, else none; "none" = no scene
    // camera path JSON, "gltf:<index|name>" or "frame"; empty: graph default (dropped when --scene
    // replaces the graph's scene)
    std::string camera;
    bool stereo = false, mono = false;  // --stereo / --mono override defaults.stereo
    // --camera-model perspective|equirect; empty: the camera path's, else the graph's
    // defaults.camera_model, else perspective.
    std::string cameraModel;
    float ipd = 0.064f;
    std::string gaze;  // "x,y" (both eyes) or "xl,yl,xr,yr"; empty = each eye's centre
    bool jitter = false;
    // Adds a white directional "sun" (3 lux, from above and slightly in front) to the scene:
    // many glTF files carry no light, and path tracing them without one renders black.
    bool sun = false;
    // --env: an equirectangular HDR image lighting the scene from infinitely far away, seen by
    // rays that leave it (docs/scenes.md "Environment light"); relative to the working
    // directory (the bench resolves its `env` key against the bench file). --env-intensity
    // scales it; --env-rotation turns it about +Y, in degrees. Combines with --sun.
    std::string env;
    float envIntensity = 1.0f;
    float envRotation = 0.0f;
    // fovea bench: ignore the graph's defaults.camera (the bench file names the camera, and
    // without one the scene's still camera is used for every graph).
    bool ignoreGraphCamera = false;
    // --allow-external-uris: glTF buffers/images outside the scene's folder may be read.
    bool allowExternalUris = false;
};

// `--camera frame`: a camera framing the scene's bounds (Scene::defaultCamera).
inline constexpr const char* kFrameCamera = "frame";

// What identifies --env and its options (file, intensity, rotation, and the file's size and
// modification time, so that a changed file under the same name is noticed): report.json's
// scene.environment and the bench's reference cache key. Null without --env.
nlohmann::json environmentKey(const SceneOptions& o);
// Every scene option as JSON, with the size of a scene or camera-path file (what a reference
// shard's key records, ReferenceShards.h).
nlohmann::json sceneOptionsKey(const SceneOptions& o);

// Parses "x,y" or "xl,yl,xr,yr" in [0,1]; errors name --gaze.
std::array<glm::vec2, scene::kMaxEyes> parseGaze(const std::string& text);

class RunScene {
public:
    // Resolves the scene and camera specs against the graph (its defaults; relative paths are
    // relative to the graph file) and loads the scene on the CPU. Throws InputError naming the
    // option or file.
    RunScene(const SceneOptions& options, const graph::GraphDesc& desc);
    ~RunScene();

    // Throws InputError naming --size when the render width leaves an eye without pixels, or
    // when an equirect camera is not 2:1.
    void checkRenderSize(uint32_t width, uint32_t height) const;
    bool hasScene() const { return mScene != nullptr; }
    const std::string& spec() const { return mSpec; }  // "none" without a scene
    uint32_t features() const;                         // graph::SceneFeature bits (CPU side)
    // Uploads geometry, BVH and lights (timed; see json()).
    void upload(gpu::Context& context);
    const scene::SceneGpu* gpu() const { return mGpu.get(); }
    // A coarse CPU trace of primary rays through `camera` (core/scene/ViewProbe.h): what share
    // hits geometry and whether the camera looks inside it. Empty without a scene or before
    // upload (the BVH built for the GPU is kept on the CPU for this).
    std::optional<scene::ViewProbe> probeView(const scene::FrameCamera& camera) const;

    // The camera of frame `frame` for an image of width x height (the whole side-by-side image
    // when stereo); remembers it as the "previous" camera of the next call. `pose` replaces the
    // path's (fovea inspect's free-fly camera).
    scene::FrameCamera frameCamera(uint64_t frame, uint32_t width, uint32_t height,
                                   const scene::CameraDesc* pose = nullptr);
    // The pose the camera path (or the scene's camera) gives frame `frame`.
    scene::CameraDesc cameraAt(uint64_t frame) const;
    bool stereo() const { return mRig.stereo; }
    scene::CameraModel cameraModel() const { return mRig.model; }

    // The scene's entry in report.json.
    nlohmann::json json() const;

private:
    std::string mSpec = "none";
    std::string mCameraSource;    // "path:<file>", "gltf:<n>", "default"
    nlohmann::json mEnvironment;  // environmentKey() + the map's size; null without --env
    std::unique_ptr<scene::Scene> mScene;
    std::unique_ptr<scene::SceneGpu> mGpu;
    std::unique_ptr<scene::Bvh> mBvh;  // the uploaded BVH, for probeView
    std::optional<scene::CameraPath> mPath;
    scene::CameraRigOptions mRig;
    std::array<glm::vec2, scene::kMaxEyes> mGaze{glm::vec2(0.5f), glm::vec2(0.5f)};
    std::optional<scene::FrameCamera> mPrevious;
    double mLoadMs = 0.0, mUploadMs = 0.0;
};

}  // namespace fovea::eval
