// glTF 2.0 scenes (--scene, defaults.scene): the whole loader (GLB container, JSON, the
// validator's structure and data checks, tinygltf, meshes, materials, textures) and the CPU work a
// loaded scene gets before the GPU (BVH build, light table). A GLB's magic picks the .glb name,
// anything else is a .gltf; buffers and images it names are looked up next to it, as for a user's
// file. Every mesh is drawn (drawEveryMesh) so meshes without nodes are checked too.
#include <cstring>

#include "core/scene/Bvh.h"
#include "core/scene/gltf/GltfLoader.h"
#include "core/scene/LightTable.h"
#include "tests/fuzz/FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace fovea;
    const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    fuzz::expectOnlyInputErrors("gltf", [&] {
        scene::GltfLoadOptions options;
        options.drawEveryMesh = true;
        const scene::Scene scene = scene::loadGltf(
            fuzz::writeInput(data, size, glb ? "scene.glb" : "scene.gltf"), options);
        const scene::Bvh bvh(scene.mesh);
        const scene::LightTable lights(scene, bvh.triangleOrder());
        (void)lights.totalPower();
    });
    return 0;
}
