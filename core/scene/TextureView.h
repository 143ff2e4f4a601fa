// How one material texture slot reads its texture: the glTF sampler (glTF 2.0 §3.8.4 / §5.26:
// wrap modes and filter) and KHR_texture_transform (offset, rotation, scale of the UVs). A value
// type of Scene::Material; the GPU form is layout::TextureView (SceneGpu.h), the CPU reference
// sampler core/scene/TextureSampling.h, the shader sceneSampleTextureView (scene_sample.glsl).
#pragma once
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>

namespace fovea::scene {

// glTF wrapS / wrapT: 10497 REPEAT (the default), 33071 CLAMP_TO_EDGE, 33648 MIRRORED_REPEAT.
enum class TextureWrap : uint32_t { Repeat = 0, ClampToEdge = 1, MirroredRepeat = 2 };

struct TextureSampler {
    TextureWrap wrapS = TextureWrap::Repeat;
    TextureWrap wrapT = TextureWrap::Repeat;
    // magFilter NEAREST (9728): the texel the UV falls in; otherwise bilinear. fovea keeps no
    // mip maps and traces no ray differentials, so minFilter has nothing to choose between and
    // is not read (docs/scenes.md).
    bool nearest = false;

    // The shader's flags word: bits 0-1 wrapS, 2-3 wrapT, 4 nearest.
    uint32_t flags() const {
        return uint32_t(wrapS) | uint32_t(wrapT) << 2 | (nearest ? 1u << 4 : 0u);
    }
    bool operator==(const TextureSampler&) const = default;
};

// KHR_texture_transform: uv' = T(offset) * R(rotation) * S(scale) * uv with the extension's
// rotation matrix as its README prints it, rows [cos sin; -sin cos]: u' = cos u + sin v,
// v' = -sin u + cos v. (The README's GLSL passes the same numbers to a column-major mat3, which
// turns the other way; the sample model TextureTransformTest, whose arrow must point at the
// green marker, settles it for the rows, as three.js and Blender's importer read it:
// tests/unit/TextureViewTests.cpp.)
struct TextureTransform {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;  // radians
    glm::vec2 scale{1.0f};

    bool isIdentity() const {
        return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f);
    }
    // The two rows of the 2x3 affine matrix: u' = dot(row0, (u, v, 1)), v' = dot(row1, ...).
    glm::vec3 row0() const {
        const float c = std::cos(rotation), s = std::sin(rotation);
        return {c * scale.x, s * scale.y, offset.x};
    }
    glm::vec3 row1() const {
        const float c = std::cos(rotation), s = std::sin(rotation);
        return {-s * scale.x, c * scale.y, offset.y};
    }
    glm::vec2 apply(const glm::vec2& uv) const {
        const glm::vec3 p(uv, 1.0f);
        return {glm::dot(row0(), p), glm::dot(row1(), p)};
    }
};

struct TextureView {
    TextureTransform transform;
    TextureSampler sampler;
};

}  // namespace fovea::scene
