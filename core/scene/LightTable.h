// Which light a shading point samples: every emissive triangle and every punctual light in one
// alias table (Vose), each picked with probability proportional to its estimated power.
//
// Selection pdf (also docs/scene-gpu.md):
//   P(light j) = Phi_j / (Phi_emissive + Phi_punctual)
// which is the same as first choosing the emissive or the punctual set with probability
// Phi_set / Phi_total and then a member of that set with Phi_j / Phi_set. The power estimates,
// all in "luminance watts" (Rec. 709 luminance of the RGB factor times the light's extent):
//   emissive triangle: Phi = pi * area * lum(emissive * avg(emissiveTexture)) * (doubleSided ? 2 :
//   1)
//                      (Lambertian emitter of radiance L emits pi * L per unit area per side;
//                       avg = the mean sRGB-decoded texel colour, 1 without a texture)
//   point:             Phi = 4 pi * intensity * lum(color)                (candela over a sphere)
//   spot:              Phi = 2 pi (1 - cos outerCone) * intensity * lum(color)
//   directional:       Phi = pi r^2 * intensity * lum(color), r = radius of the scene's bounding
//                      sphere (the flux the light pours through the scene's cross-section)
// Any positive weights keep the estimator unbiased; these only decide where samples go.
#pragma once
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "core/scene/Scene.h"

namespace fovea::scene {

// Set in EmitterEntry::light for punctual lights (index into Scene::lights in the low bits).
inline constexpr uint32_t kEmitterPunctualBit = 0x80000000u;

// One alias-table entry as the GPU reads it (struct SceneEmitter in scene_data.glsl). Sampling:
// column c = floor(u0 * N); keep c when u1 < aliasProb, else take entry `alias`.
struct EmitterEntry {
    uint32_t light = 0;  // emissive: GPU triangle index (Bvh order); punctual: bit | light index
    uint32_t alias = 0;
    float aliasProb = 1.0f;
    float pdf = 0.0f;  // selection probability of this light: Phi_j / Phi_total
};
static_assert(sizeof(EmitterEntry) == 16, "EmitterEntry must match the 16-byte GLSL struct");

struct AliasSlot {
    double prob = 1.0;
    uint32_t alias = 0;
};
// Vose's alias method over non-negative weights with a positive finite sum; an empty vector
// otherwise. Sampling slot i with probability 1/N and keeping it with `prob` (else `alias`)
// draws index j with probability weights[j] / sum.
std::vector<AliasSlot> buildAliasTable(const std::vector<double>& weights);

class LightTable {
public:
    // triangleOrder maps GPU triangle positions to mesh triangles (Bvh::triangleOrder()); empty
    // means identity. Triangles, materials or lights that are non-finite or emit nothing are left
    // out. Throws RuntimeError when the order's size differs from the triangle count.
    LightTable(const Scene& scene, const std::vector<uint32_t>& triangleOrder = {});

    // Emissive triangles (ascending GPU index) then punctual lights (ascending index), each with
    // power > 0. Empty when nothing emits.
    const std::vector<EmitterEntry>& entries() const { return mEntries; }
    double emissivePower() const { return mEmissivePower; }
    double punctualPower() const { return mPunctualPower; }
    double totalPower() const { return mEmissivePower + mPunctualPower; }
    uint32_t emissiveTriangleCount() const { return mEmissiveTriangles; }
    uint32_t punctualLightCount() const { return mPunctualLights; }
    // Per material: emitted power per unit area, pi * lum(emissive * avg texture) * sides, so
    // a shader recovers a hit emitter's selection pdf as density * area / totalPower.
    const std::vector<double>& materialPowerDensity() const { return mMaterialDensity; }
    // Per Scene::lights entry: its Phi (0 for lights that emit nothing).
    const std::vector<double>& punctualPowers() const { return mPunctualPowers; }

    static double luminance(const glm::dvec3& c) {
        return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    }
    static double srgbToLinear(double c);
    // Mean sRGB-decoded RGB of a texture; (1,1,1) for one without texels.
    static glm::dvec3 averageLinearColor(const Texture& texture);
    static double punctualPower(const Light& light, const Bounds& sceneBounds);
    static double triangleArea(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);

private:
    std::vector<EmitterEntry> mEntries;
    std::vector<double> mMaterialDensity;
    std::vector<double> mPunctualPowers;
    double mEmissivePower = 0.0;
    double mPunctualPower = 0.0;
    uint32_t mEmissiveTriangles = 0;
    uint32_t mPunctualLights = 0;
};

}  // namespace fovea::scene
