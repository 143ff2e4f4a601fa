// glTF materials to fovea materials, converted on first use so that only what the scene draws
// ends up in Scene::materials / Scene::textures (each image decoded once, however many textures
// or materials share it). Emission is emissiveFactor x KHR_materials_emissive_strength; factors
// above 1 are kept (HDR emitters are common in real files, e.g. NVIDIA's Cornell box).
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/scene/gltf/GltfDocument.h"
#include "core/scene/Scene.h"
#include "core/scene/gltf/TinyGltf.h"

namespace fovea::scene::gltf {

// The material primitives without one get (header Scene.h): grey, diffuse.
Material defaultMaterial();

class MaterialTable {
public:
    MaterialTable(const GltfDocument& doc, const tinygltf::Model& model, Scene& scene,
                  std::vector<std::string>& warnings)
        : mDoc(doc), mModel(model), mScene(scene), mWarnings(warnings) {}

    // Scene material id for glTF material `index` (-1 = none: the default material).
    uint32_t idFor(int index);

private:
    // Scene texture of a material's texture info (-1 = none), and how the slot reads it: the
    // texture's sampler and the info's KHR_texture_transform.
    // `index`: the info's texture (-1 = none); `pointer` names the info in the JSON.
    int textureFor(int index, const std::string& pointer, TextureView& view);
    Material convert(size_t index);

    const GltfDocument& mDoc;
    const tinygltf::Model& mModel;
    Scene& mScene;
    std::vector<std::string>& mWarnings;
    std::map<int, uint32_t> mMaterials;  // glTF material (-1 = default) -> scene id
    std::map<int, int> mImages;          // glTF image -> scene texture
};

}  // namespace fovea::scene::gltf
