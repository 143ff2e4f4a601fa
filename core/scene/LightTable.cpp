#include "core/scene/LightTable.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "core/util/Error.h"

namespace fovea::scene {
namespace {

double finiteOrZero(double v) {
    return std::isfinite(v) && v > 0.0 ? v : 0.0;
}

// The light-selection weight of a colour: its luminance, never negative or NaN.
double colourWeight(const glm::dvec3& c) {
    return finiteOrZero(LightTable::luminance(c));
}

Bounds finiteBounds(const TriangleMesh& mesh) {
    Bounds b;
    for (const auto& p : mesh.positions)
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) b.grow(p);
    return b;
}

}  // namespace

std::vector<AliasSlot> buildAliasTable(const std::vector<double>& weights) {
    double sum = 0.0;
    for (double w : weights) {
        if (!(w >= 0.0) || !std::isfinite(w)) return {};
        sum += w;
    }
    if (!(sum > 0.0) || !std::isfinite(sum)) return {};
    const size_t n = weights.size();
    std::vector<AliasSlot> table(n);
    std::vector<double> scaled(n);
    std::vector<uint32_t> small, large;
    for (size_t i = 0; i < n; ++i) {
        scaled[i] = weights[i] * double(n) / sum;  // sum > 0 checked above
        table[i].alias = static_cast<uint32_t>(i);
        (scaled[i] < 1.0 ? small : large).push_back(static_cast<uint32_t>(i));
    }
    while (!small.empty() && !large.empty()) {
        const uint32_t l = small.back(), g = large.back();
        small.pop_back();
        large.pop_back();
        table[l].prob = scaled[l];
        table[l].alias = g;
        // g gives away what fills l's column up to 1.
        scaled[g] = (scaled[g] + scaled[l]) - 1.0;
        (scaled[g] < 1.0 ? small : large).push_back(g);
    }
    // Leftovers are 1 up to rounding: they keep their own column.
    for (uint32_t i : large) table[i] = {1.0, i};
    for (uint32_t i : small) table[i] = {1.0, i};
    return table;
}

double LightTable::srgbToLinear(double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

glm::dvec3 LightTable::averageLinearColor(const Texture& texture) {
    const size_t texels = size_t(texture.width) * texture.height;
    if (texels == 0 || texture.rgba8.size() < texels * 4) return glm::dvec3(1.0);
    std::array<double, 256> lut;
    for (int i = 0; i < 256; ++i) lut[i] = srgbToLinear(i / 255.0);
    glm::dvec3 sum(0.0);
    for (size_t i = 0; i < texels; ++i) {
        const uint8_t* t = &texture.rgba8[i * 4];
        sum += glm::dvec3(lut[t[0]], lut[t[1]], lut[t[2]]);
    }
    return sum / double(texels);  // texels > 0 checked above
}

double LightTable::punctualPower(const Light& light, const Bounds& sceneBounds) {
    const double pi = std::numbers::pi;
    const double radiant = finiteOrZero(light.intensity) * colourWeight(glm::dvec3(light.color));
    switch (light.type) {
        case Light::Type::Point:
            return 4.0 * pi * radiant;
        case Light::Type::Spot: {
            // The extension caps the outer cone at pi/2; clamp so the solid angle stays sane.
            const double outer = std::clamp(double(light.outerConeAngle), 0.0, pi / 2.0);
            return 2.0 * pi * (1.0 - std::cos(outer)) * radiant;
        }
        case Light::Type::Directional: {
            double r = 0.5 * glm::length(glm::dvec3(sceneBounds.extent()));
            if (!(r > 0.0) || !std::isfinite(r)) r = 1.0;  // point-sized or empty scene
            return pi * r * r * radiant;
        }
    }
    return 0.0;
}

double LightTable::triangleArea(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::dvec3 e1 = glm::dvec3(b) - glm::dvec3(a), e2 = glm::dvec3(c) - glm::dvec3(a);
    return finiteOrZero(0.5 * glm::length(glm::cross(e1, e2)));
}

LightTable::LightTable(const Scene& scene, const std::vector<uint32_t>& triangleOrder) {
    const TriangleMesh& mesh = scene.mesh;
    if (!triangleOrder.empty() && triangleOrder.size() != mesh.triangles.size())
        throw RuntimeError("LightTable: triangle order has " +
                           std::to_string(triangleOrder.size()) + " entries for " +
                           std::to_string(mesh.triangles.size()) + " triangles");

    mMaterialDensity.resize(scene.materials.size(), 0.0);
    for (size_t m = 0; m < scene.materials.size(); ++m) {
        const Material& mat = scene.materials[m];
        if (!mat.isEmissive()) continue;
        glm::dvec3 colour(mat.emissive);
        const int tex = mat.emissiveTexture;
        if (tex >= 0 && size_t(tex) < scene.textures.size())
            colour *= averageLinearColor(scene.textures[tex]);
        mMaterialDensity[m] = std::numbers::pi * colourWeight(colour) * (mat.doubleSided ? 2 : 1);
    }

    std::vector<double> weights;
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
        const size_t t = triangleOrder.empty() ? i : triangleOrder[i];
        if (t >= mesh.triangles.size() || t >= mesh.materialIds.size()) continue;
        const uint32_t material = mesh.materialIds[t];
        if (material >= mMaterialDensity.size() || mMaterialDensity[material] <= 0.0) continue;
        const glm::uvec3& tri = mesh.triangles[t];
        if (std::max({tri.x, tri.y, tri.z}) >= mesh.positions.size()) continue;
        const double power =
            mMaterialDensity[material] *
            triangleArea(mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z]);
        if (!(power > 0.0) || !std::isfinite(power)) continue;
        mEntries.push_back(EmitterEntry{.light = static_cast<uint32_t>(i)});
        weights.push_back(power);
        mEmissivePower += power;
    }
    mEmissiveTriangles = static_cast<uint32_t>(mEntries.size());

    const Bounds bounds = finiteBounds(mesh);
    mPunctualPowers.resize(scene.lights.size(), 0.0);
    for (size_t l = 0; l < scene.lights.size() && l < kEmitterPunctualBit; ++l) {
        const double power = punctualPower(scene.lights[l], bounds);
        if (!(power > 0.0) || !std::isfinite(power)) continue;
        mPunctualPowers[l] = power;
        mEntries.push_back(EmitterEntry{.light = kEmitterPunctualBit | static_cast<uint32_t>(l)});
        weights.push_back(power);
        mPunctualPower += power;
    }
    mPunctualLights = static_cast<uint32_t>(mEntries.size()) - mEmissiveTriangles;

    const std::vector<AliasSlot> alias = buildAliasTable(weights);
    if (alias.empty()) {  // the sum overflowed (absurd intensities): nothing is sampleable
        mEntries.clear();
        mEmissivePower = mPunctualPower = 0.0;
        mEmissiveTriangles = mPunctualLights = 0;
        return;
    }
    const double total = totalPower();
    for (size_t i = 0; i < mEntries.size(); ++i) {
        mEntries[i].alias = alias[i].alias;
        mEntries[i].aliasProb = static_cast<float>(alias[i].prob);
        mEntries[i].pdf = static_cast<float>(weights[i] / total);  // total > 0: alias not empty
    }
}

}  // namespace fovea::scene
