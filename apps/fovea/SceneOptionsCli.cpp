// The scene options every command that runs a graph shares (--scene, --camera, --stereo, ...),
// as CLI11 options filling eval::SceneOptions (eval/run/SceneSetup.h).
#include "apps/fovea/CliChecks.h"
#include "apps/fovea/Commands.h"

namespace fovea::app {

void addSceneOptions(CLI::App& cmd, SceneOptions& o) {
    cmd.add_option("--scene", o.scene,
                   "scene: builtin:<name> or a .gltf/.glb file; 'none' for none (default: the "
                   "graph's defaults.scene)")
        ->check(nonEmptyValue())
        ->check(userPath());
    cmd.add_option("--camera", o.camera,
                   "camera path JSON (docs/camera-path.md), gltf:<index|name>, or 'frame' (a "
                   "camera framing the scene) (default: the graph's defaults.camera unless "
                   "--scene replaces its scene, else the scene's first camera, else 'frame')")
        ->check(nonEmptyValue())
        ->check(userPath());
    cmd.add_flag("--stereo", o.stereo, "side-by-side stereo rig (seed 000 §3.1)");
    cmd.add_flag("--mono", o.mono, "one eye, even if the graph defaults to stereo");
    cmd.add_option("--camera-model", o.cameraModel,
                   "perspective, or equirect: a 360° latitude-longitude camera whose image is "
                   "2:1 (seed 003 P4; default: the camera path's camera_model, else the graph's "
                   "defaults.camera_model, else perspective)")
        ->check(CLI::IsMember({"perspective", "equirect"}));
    cmd.add_option("--ipd", o.ipd, "interpupillary distance in scene units (default 0.064)")
        ->check(finiteRange(0.0, 10.0));
    cmd.add_option("--gaze", o.gaze,
                   "gaze point in [0,1]^2 of each eye's image: x,y or xl,yl,xr,yr (default: the "
                   "centre; a camera path may override it per key)")
        ->check(nonEmptyValue());
    cmd.add_flag("--allow-external-uris", o.allowExternalUris,
                 "let a glTF file read buffers/images outside its folder (absolute paths, ../)");
    cmd.add_flag("--jitter", o.jitter, "Halton (2,3) sub-pixel jitter per frame (for TAA)");
    cmd.add_flag("--sun", o.sun,
                 "add a white directional light (3 lux from above) to the scene, e.g. for glTF "
                 "files without lights");
    cmd.add_option("--env", o.env,
                   "environment light: an equirectangular (2:1 latitude-longitude) HDR image, EXR "
                   "or Radiance .hdr, lighting the scene from all around and seen as its "
                   "background (docs/scenes.md)")
        ->check(nonEmptyValue())
        ->check(userPath());
    cmd.add_option("--env-intensity", o.envIntensity, "scale of the --env radiance (default 1)")
        ->check(finiteRange(0.0, 1e9));
    cmd.add_option("--env-rotation", o.envRotation,
                   "rotation of the --env map about the up axis (+Y), degrees (default 0: the "
                   "image centre faces +X)")
        ->check(finiteRange(-36000.0, 36000.0));
}

}  // namespace fovea::app
