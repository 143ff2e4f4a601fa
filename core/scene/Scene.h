// The CPU-side scene every loader produces and every GPU upload consumes: one flattened
// world-space triangle mesh (node transforms baked in), glTF metallic-roughness materials,
// decoded textures, punctual lights and cameras. Flattening keeps the BVH single-level and the
// shaders free of instance indirection; the scenes of the documents are static.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/scene/TextureView.h"

namespace fovea::scene {

struct EnvironmentMap;  // core/scene/Environment.h

struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{-std::numeric_limits<float>::max()};
    void grow(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    bool empty() const { return min.x > max.x; }
    glm::vec3 center() const { return 0.5f * (min + max); }
    glm::vec3 extent() const { return empty() ? glm::vec3(0.0f) : max - min; }
};

// glTF 2.0 §3.9.4 alpha coverage: OPAQUE ignores alpha; MASK drops texels whose alpha is below
// alphaCutoff; BLEND is traced as stochastic transparency (docs/scenes.md "Alpha").
enum class AlphaMode : uint32_t { Opaque = 0, Mask = 1, Blend = 2 };

// glTF 2.0 metallic-roughness material. Texture fields index Scene::textures (-1 = none).
struct Material {
    std::string name;
    glm::vec4 baseColor{1.0f};  // linear RGBA factor
    int baseColorTexture = -1;  // sRGB-encoded texels
    glm::vec3 emissive{0.0f};   // linear factor, already multiplied by emissive_strength
    int emissiveTexture = -1;   // sRGB-encoded texels
    float metallic = 1.0f;      // glTF defaults
    float roughness = 1.0f;
    int metallicRoughnessTexture = -1;  // linear; G = roughness, B = metallic
    // glTF 2.0 §3.9.3 normal texture (linear; tangent space, needs TriangleMesh::tangents) and
    // its `scale` (x and y of the sampled normal are multiplied by it).
    int normalTexture = -1;
    float normalScale = 1.0f;
    // How each texture is read: its glTF sampler and KHR_texture_transform (TextureView.h).
    TextureView baseColorView, emissiveView, metallicRoughnessView, normalView;
    bool doubleSided = false;
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;  // glTF default; read only in MASK mode (>= 0, validated)
    bool isEmissive() const { return emissive.r > 0.0f || emissive.g > 0.0f || emissive.b > 0.0f; }
    // Some texels may let rays through: BLEND, or MASK with a cutoff above 0 (alpha >= 0 always
    // meets a cutoff of 0, so that MASK draws exactly like OPAQUE).
    bool hasAlphaTest() const {
        return alphaMode == AlphaMode::Blend ||
               (alphaMode == AlphaMode::Mask && alphaCutoff > 0.0f);
    }
};

// Decoded 8-bit RGBA texels, row-major, top row first (glTF UV origin is the top-left).
struct Texture {
    std::string name;
    uint32_t width = 0, height = 0;
    std::vector<uint8_t> rgba8;
};

// KHR_lights_punctual, in world space. Intensity units as the extension: candela for point and
// spot lights, lux for directional ones.
struct Light {
    enum class Type : uint32_t { Point = 0, Spot = 1, Directional = 2 };
    Type type = Type::Point;
    std::string name;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // the way the light shines (normalized)
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
    float range = 0.0f;  // 0 = infinite
    float innerConeAngle = 0.0f;
    float outerConeAngle = 0.7853982f;  // pi/4, the extension's default
};

// A pinhole camera in world space.
struct CameraDesc {
    std::string name;
    glm::vec3 position{0.0f, 0.0f, 1.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float yfov = 0.8f;  // vertical field of view, radians
    float znear = 0.01f;
};

// Flattened world-space triangles: positions/normals/uvs are per vertex, `triangles` index them,
// `materialIds` has one entry per triangle.
struct TriangleMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;  // normalized; generated flat when the file has none
    std::vector<glm::vec2> uvs;      // (0,0) when the file has none
    // glTF COLOR_0, linear RGBA in [0, 1] per vertex (glTF 2.0 §3.7.2.1: multiplies the base
    // colour). Empty when no primitive has one; else one per position, (1,1,1,1) for vertices of
    // primitives without COLOR_0.
    std::vector<glm::vec4> colors;
    // Tangent frames for normal textures (glTF TANGENT: xyz unit tangent along +u, w = +-1 the
    // bitangent's sign, B = cross(N, T) * w), from the file or generated (core/scene/Tangents.h).
    // Empty when no primitive is normal-mapped; else one per position, (0,0,0,1) for vertices
    // of primitives without a normal texture.
    std::vector<glm::vec4> tangents;
    std::vector<glm::uvec3> triangles;
    std::vector<uint32_t> materialIds;
    size_t triangleCount() const { return triangles.size(); }
};

struct Scene {
    std::string source;  // file path or "builtin:<name>"
    TriangleMesh mesh;
    std::vector<Material> materials;  // never empty once loaded (a default grey one is added)
    std::vector<Texture> textures;
    std::vector<Light> lights;
    std::vector<CameraDesc> cameras;    // from the file; may be empty
    std::vector<std::string> warnings;  // broken entries nothing uses, ignored optional extensions
    Bounds bounds;                      // of mesh.positions
    // Radiance from infinitely far away (--env); null = none (misses see black). Shared: the
    // map can be large and scenes are copied (test rigs, per-run setup).
    std::shared_ptr<const EnvironmentMap> environment;

    // SceneFeature bits (core/scene/SceneFeatures.h) this scene provides.
    uint32_t features() const;
    // A camera that frames the bounding box (docs/scenes.md): looks down -Z at the box centre
    // from a distance where the box's bounding sphere fits a 45 degree vertical FOV.
    CameraDesc defaultCamera() const;
};

}  // namespace fovea::scene
