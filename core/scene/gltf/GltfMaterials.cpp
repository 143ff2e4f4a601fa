#include "core/scene/gltf/GltfMaterials.h"

#include <algorithm>
#include <cstdio>

#include "core/scene/gltf/GltfJson.h"
#include "core/scene/gltf/GltfLayout.h"
#include "core/scene/gltf/GltfTextures.h"
#include "core/scene/gltf/GltfUsage.h"
#include "core/util/Error.h"

namespace fovea::scene::gltf {

namespace {

float unit(double v) {
    return float(std::clamp(v, 0.0, 1.0));
}

// glTF 2.0 §5.26 sampler: wrap modes by their GL enums; magFilter NEAREST (9728) samples the
// nearest texel (TextureView.h: minFilter is not read, fovea keeps no mip maps). Values were
// validated (GltfValidate); anything else keeps the default.
TextureSampler samplerOf(const tinygltf::Sampler& s) {
    auto wrap = [](int mode) {
        switch (mode) {
            case 33071:
                return TextureWrap::ClampToEdge;
            case 33648:
                return TextureWrap::MirroredRepeat;
            default:
                return TextureWrap::Repeat;  // 10497, the default
        }
    };
    TextureSampler out;
    out.wrapS = wrap(s.wrapS);
    out.wrapT = wrap(s.wrapT);
    out.nearest = s.magFilter == 9728;
    return out;
}

// KHR_texture_transform of a texture info (identity without the extension; values validated).
TextureTransform textureTransformOf(const JsonView& info) {
    TextureTransform t;
    JsonView ext = info.object("extensions").object("KHR_texture_transform");
    if (!ext.isObject()) return t;
    if (auto offset = ext.numbers("offset", 2)) t.offset = glm::vec2((*offset)[0], (*offset)[1]);
    if (auto rotation = ext.number("rotation")) t.rotation = float(*rotation);
    if (auto scale = ext.numbers("scale", 2)) t.scale = glm::vec2((*scale)[0], (*scale)[1]);
    return t;
}

}  // namespace

Material defaultMaterial() {
    Material m;
    m.name = "default";
    m.baseColor = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
    m.metallic = 0.0f;
    m.roughness = 1.0f;
    return m;
}

uint32_t MaterialTable::idFor(int index) {
    if (index >= 0 && size_t(index) >= mModel.materials.size()) {
        throw InputError(mDoc.file, "/materials/" + std::to_string(index), "material missing");
    }
    auto found = mMaterials.find(index);
    if (found != mMaterials.end()) return found->second;
    Material material = index < 0 ? defaultMaterial() : convert(size_t(index));
    uint32_t id = uint32_t(mScene.materials.size());
    mScene.materials.push_back(std::move(material));
    mMaterials.emplace(index, id);
    return id;
}

int MaterialTable::textureFor(int index, const std::string& pointer, TextureView& view) {
    view = TextureView{};
    if (index < 0) return -1;
    // The texture info as written (GltfValidate checked the extension's values).
    JsonView raw(&mDoc.json.at(nlohmann::json::json_pointer(pointer)), pointer, nullptr);
    // GltfUsage warned: only TEXCOORD_0 is supported (after KHR_texture_transform's override).
    if (effectiveTexCoord(raw) != 0) return -1;
    if (size_t(index) >= mModel.textures.size()) {
        throw InputError(mDoc.file, pointer + "/index", "texture missing");
    }
    const tinygltf::Texture& gltfTexture = mModel.textures[size_t(index)];
    if (gltfTexture.sampler >= 0 && size_t(gltfTexture.sampler) < mModel.samplers.size())
        view.sampler = samplerOf(mModel.samplers[size_t(gltfTexture.sampler)]);
    view.transform = textureTransformOf(raw);
    int image = gltfTexture.source;
    if (image < 0) {
        // glTF 2.0 allows a texture without source (an extension may supply one); none of those
        // extensions is supported, so the texture is dropped, loudly.
        mWarnings.push_back("/textures/" + std::to_string(index) +
                            ": no image source (unsupported texture extension?); the texture "
                            "is ignored by " +
                            pointer);
        return -1;
    }
    auto found = mImages.find(image);
    if (found != mImages.end()) return found->second;
    Texture texture = decodeImage(mDoc, mModel, size_t(image));
    int id = int(mScene.textures.size());
    mScene.textures.push_back(std::move(texture));
    mImages.emplace(image, id);
    return id;
}

Material MaterialTable::convert(size_t index) {
    const tinygltf::Material& src = mModel.materials[index];
    std::string pointer = "/materials/" + std::to_string(index);
    Material m;
    m.name = src.name.empty() ? "material " + std::to_string(index) : src.name;
    const tinygltf::PbrMetallicRoughness& pbr = src.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() == 4) {
        m.baseColor = glm::vec4(unit(pbr.baseColorFactor[0]), unit(pbr.baseColorFactor[1]),
                                unit(pbr.baseColorFactor[2]), unit(pbr.baseColorFactor[3]));
    }
    m.metallic = unit(pbr.metallicFactor);
    m.roughness = unit(pbr.roughnessFactor);
    m.baseColorTexture =
        textureFor(pbr.baseColorTexture.index, pointer + "/pbrMetallicRoughness/baseColorTexture",
                   m.baseColorView);
    m.metallicRoughnessTexture = textureFor(
        pbr.metallicRoughnessTexture.index,
        pointer + "/pbrMetallicRoughness/metallicRoughnessTexture", m.metallicRoughnessView);
    m.emissiveTexture =
        textureFor(src.emissiveTexture.index, pointer + "/emissiveTexture", m.emissiveView);
    // §3.9.3: a tangent-space normal texture; its scale multiplies the sampled x and y.
    m.normalTexture = textureFor(src.normalTexture.index, pointer + "/normalTexture", m.normalView);
    m.normalScale = float(src.normalTexture.scale);
    m.doubleSided = src.doubleSided;

    // KHR_materials_emissive_strength is read from the raw JSON (validated there).
    JsonView raw(&mDoc.json.at("materials").at(index), pointer, nullptr);
    double strength = raw.object("extensions")
                          .object("KHR_materials_emissive_strength")
                          .number("emissiveStrength")
                          .value_or(1.0);
    if (src.emissiveFactor.size() == 3) {
        glm::dvec3 factor(src.emissiveFactor[0], src.emissiveFactor[1], src.emissiveFactor[2]);
        if (factor.x > 1.0 || factor.y > 1.0 || factor.z > 1.0) {
            mWarnings.push_back(pointer +
                                "/emissiveFactor: above 1 (outside the glTF range); kept as an "
                                "HDR emission");
        }
        // 1e39 became +inf in 32 bits and 1e30 overflows once squared (variance, regression):
        // the image came out black with exit 0. Emission is capped like scene coordinates.
        const glm::dvec3 emission = factor * strength;
        const double largest = std::max({emission.x, emission.y, emission.z});
        if (!(largest <= kMaxEmission)) {
            char value[32];
            std::snprintf(value, sizeof value, "%g", largest);
            throw InputError(mDoc.file, pointer + "/emissiveFactor",
                             std::string("emission (emissiveFactor x emissiveStrength) of ") +
                                 value + " is above 1e15: it overflows 32-bit float radiance sums");
        }
        m.emissive = glm::vec3(emission);
    }
    // glTF 2.0 §3.9.4 (alpha coverage); the validator accepted only the three modes and a
    // finite alphaCutoff >= 0 (schema minimum 0, default 0.5). Any cutoff above 1 hides every
    // texel (alpha <= 1); capping it at 2 keeps the float finite without changing that.
    if (src.alphaMode == "MASK") {
        m.alphaMode = AlphaMode::Mask;
        m.alphaCutoff = float(std::clamp(src.alphaCutoff, 0.0, 2.0));
    } else if (src.alphaMode == "BLEND") {
        m.alphaMode = AlphaMode::Blend;  // traced as stochastic transparency (docs/scenes.md)
    }
    return m;
}

}  // namespace fovea::scene::gltf
