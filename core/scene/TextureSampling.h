// The CPU reference of the shaders' texture lookup (sceneSampleTextureView, scene_sample.glsl):
// KHR_texture_transform, the sampler's wrap modes, nearest or bilinear filtering with texel
// centres at (i + 0.5) / size, and sRGB decoding per texel before filtering. Tests compare the
// GPU against it; the texture transform sample model is checked with it.
#pragma once
#include <glm/glm.hpp>

#include "core/scene/Scene.h"

namespace fovea::scene {

// The texel index `i` (any integer) wraps to in [0, size) (size >= 1).
int wrapTexel(int i, int size, TextureWrap wrap);

// RGBA at `uv` (before the view's transform is applied) of `texture` read through `view`;
// (1, 1, 1, 1) for a texture without texels, like the shader.
glm::vec4 sampleTexture(const Texture& texture, const TextureView& view, glm::vec2 uv, bool srgb);

}  // namespace fovea::scene
