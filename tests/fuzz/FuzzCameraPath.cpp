// Camera path files (--camera, a graph's defaults.camera): the reader with its checks, then the
// interpolation at every frame of the path (Catmull-Rom, FOV, gaze, cuts) up to a bounded count.
#include <algorithm>

#include "core/scene/CameraPath.h"
#include "tests/fuzz/FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace fovea;
    fuzz::expectOnlyInputErrors("camera_path", [&] {
        const scene::CameraPath path =
            scene::CameraPath::load(fuzz::writeInput(data, size, "camera.json"));
        const uint64_t frames = std::min<uint64_t>(path.length() + 2, 4096);
        for (uint64_t f = 0; f < frames; ++f) (void)path.at(f);
        (void)path.at(~uint64_t(0));
    });
    return 0;
}
