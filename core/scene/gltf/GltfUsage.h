// Step 2 of loading a glTF file: what the scene uses. Picks the scene (the default scene, else
// scene 0, else every root node), walks its node hierarchy with world transforms, and follows the
// references of what it meets: nodes -> meshes -> rendered primitives -> accessors -> buffer views
// -> buffers, materials -> textures -> images/samplers, cameras, lights. The result decides
// whether a problem is fatal (the scene uses the entity) or only a warning (nothing uses it).
// Also checks the node graph itself: a node with two parents, cycles, scene roots that are not
// roots. The walk never trusts the JSON: out-of-range references are skipped here (and recorded
// by GltfValidate), and no node is visited twice, so cycles cannot hang it.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene/gltf/GltfJson.h"

namespace fovea::scene::gltf {

// One drawn node: its world transform and the mesh it draws (-1 = none). With
// drawEveryMesh, meshes no node draws get an instance of their own, with node = -1.
struct NodeInstance {
    int64_t node = -1;
    int64_t mesh = -1;
    glm::dmat4 world{1.0};
};

struct GltfUsage {
    int64_t scene = -1;                   // the scene rendered; -1 = all root nodes (no scenes)
    std::vector<NodeInstance> instances;  // used nodes, depth-first, with world transforms
    std::vector<char> nodes, meshes, accessors, bufferViews, buffers, materials, textures, images,
        samplers, cameras, lights;
    std::vector<std::vector<char>> primitives;  // [mesh][primitive]: rendered (mode 4, POSITION)

    // True if the JSON pointer lies in (or contains) something the scene uses. Pointers outside
    // the entity collections (the root, /asset, /extensionsRequired, ...) always count as used.
    bool isUsed(std::string_view pointer) const;
    // Entity-level pointers of everything used ("/nodes/0", "/meshes/0/primitives/1", ...).
    std::vector<std::string> pointers() const;
};

// `warnings` receives notes about used things that are ignored (skins, morph targets, primitives
// that are not triangle lists). `drawEveryMesh`: see GltfLoadOptions.
GltfUsage computeUsage(const GltfJson& gltf, std::vector<std::string>& warnings,
                       bool drawEveryMesh = false);

// The local transform of a node (matrix, or T * R * S); reads silently, GltfValidate reports.
glm::dmat4 nodeLocalTransform(const JsonView& node);

// The texture-info members of a material that fovea reads (glTF name, pointer suffix).
struct TextureSlot {
    const char* owner;  // "" or "pbrMetallicRoughness"
    const char* name;   // "baseColorTexture", ...
};
const std::vector<TextureSlot>& renderedTextureSlots();

// The TEXCOORD_<n> a texture info reads: KHR_texture_transform's `texCoord` overrides the
// info's own (the extension's README, "texCoord"); 0 when neither says.
uint64_t effectiveTexCoord(const JsonView& info);

}  // namespace fovea::scene::gltf
