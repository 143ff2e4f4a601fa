// Environment light: an equirectangular (latitude-longitude) HDR image of the radiance arriving
// from infinitely far away, and the distribution that importance-samples it (docs/scenes.md
// "Environment light"; the GPU side is shaders/common/environment.glsl).
//
// Direction convention, chosen to match Blender Cycles' equirectangular world after Blender's
// glTF importer turns glTF's +Y up into +Z up, so one EXR lights both renderers the same way:
//   theta = acos(y) (0 at +Y, the zenith),  phi = atan2(z, x) + rotation
//   column u = 0.5 + phi / (2 pi),  row v = theta / pi  (row 0 = top of the image = zenith)
// The image centre (u = 0.5, v = 0.5) faces +X for rotation 0; a rotation of r radians turns the
// map about +Y (the centre then faces (cos r, 0, -sin r)).
//
// Sampling (pbrt-v3 §14.2.4's piecewise-constant lat-long distribution, each 1-D step drawn with
// an alias table instead of a CDF: O(1) per sample): texel (i, j) has probability
//   P_ij = lum(L_ij) sin(theta_j) / sum,  drawn as P(row j) * P(column i | row j),
// the point inside the texel uniformly in (u, v); the solid-angle pdf of direction w in texel
// (i, j) is p(w) = P_ij * W * H / (2 pi^2 sin(theta(w))). Two small tables rather than one over
// all texels: a 24-bit random number picks one of N slots without measurable bias only while N
// is far below 2^24, and a row or a column has at most kMaxEnvironmentSide entries.
#pragma once
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/scene/LightTable.h"

namespace fovea::scene {

// Larger maps are halved (2x2 box filter, power preserved) until both sides fit, with a warning:
// 8192 keeps an 8K HDRI's full width; the slot granularity of a 24-bit random number is then
// 8192 / 2^24 = 0.05 % (see the header comment).
inline constexpr uint32_t kMaxEnvironmentSide = 8192;
// Larger files are refused before their pixels are read (a 16K x 8K map would take 4 GiB as
// float RGBA twice over): 2^26 = 8192 x 8192.
inline constexpr uint64_t kMaxEnvironmentPixels = uint64_t(1) << 26;

struct EnvironmentMap {
    std::string source;  // file path (for messages and reports)
    uint32_t width = 0, height = 0;
    std::vector<glm::vec3> radiance;  // linear RGB, intensity applied, row-major, top row first
    float intensity = 1.0f;           // already applied to `radiance`; kept for reports
    float rotation = 0.0f;            // radians about +Y (see the header comment)
};

// Reads an equirectangular EXR or Radiance .hdr (or any format core/image/ImageIO.h reads; others
// are read as linear values, with a warning) and scales it by `intensity`. InputError naming the
// file for: a missing, unreadable or empty file, a NaN or infinite texel (names the first one);
// naming the option for a non-finite or negative intensity or a non-finite rotation. Appends to
// `warnings` (the picture is still defined) when the aspect is not 2:1 (the image is stretched
// over the sphere as it is), when negative texels were clamped to 0 (lossy EXRs hold tiny ones),
// when the map was downsampled, or when every texel is black (the
// environment then lights nothing and is not uploaded).
EnvironmentMap loadEnvironment(const std::filesystem::path& path, float intensity,
                               float rotationDegrees, std::vector<std::string>& warnings);

// An environment of one radiance everywhere (tests, white furnaces): width x height texels.
EnvironmentMap constantEnvironment(const glm::vec3& radiance, uint32_t width = 8,
                                   uint32_t height = 4);

// The continuous (u, v) in [0, 1)^2 that direction `dir` maps to (need not be normalized; zero
// gives the zenith), and its inverse.
glm::vec2 environmentUv(const glm::vec3& dir, float rotation);
glm::vec3 environmentDirection(const glm::vec2& uv, float rotation);
// The radiance of the texel `dir` falls in (nearest texel: the pdf is constant per texel).
glm::vec3 environmentRadiance(const EnvironmentMap& map, const glm::vec3& dir);

// The sampling distribution (CPU reference of shaders/common/environment.glsl; uploaded by
// SceneGpu). Empty (power 0) when the map is black.
class EnvironmentDistribution {
public:
    explicit EnvironmentDistribution(const EnvironmentMap& map);

    bool empty() const { return mRows.empty(); }
    // Per texel: selection probability P_ij (sums to 1).
    const std::vector<double>& texelProbability() const { return mTexelProbability; }
    // Alias table over rows (height slots), then one over each row's columns (width slots a
    // row, row-major; a row of probability 0 holds a uniform dummy table).
    const std::vector<AliasSlot>& rows() const { return mRows; }
    const std::vector<AliasSlot>& columns() const { return mColumns; }
    // The texel drawn from three uniform numbers in [0, 1) as the shader draws it: u.x picks a
    // row slot, u.y keeps it or takes its alias; u.z and the coin u.w likewise pick the column.
    uint32_t sampleTexel(const glm::vec4& u) const;
    // Solid-angle pdf of sampling direction `dir` (0 where sin theta = 0 or the texel is black).
    double pdf(const glm::vec3& dir) const;
    // Integral of luminance over the sphere, sum lum(L_ij) * solidAngle_ij (sr * radiance).
    double luminanceIntegral() const { return mLuminanceIntegral; }
    // Selection weight against the scene's other lights, in LightTable's units: the map as a
    // sum of directional lights, each solid angle dw giving pi r^2 L dw as a directional light
    // gives pi r^2 E (r = the scene's bounding radius): pi r^2 * luminanceIntegral.
    double power(double sceneRadius) const;

private:
    uint32_t mWidth = 0, mHeight = 0;
    float mRotation = 0.0f;
    std::vector<double> mTexelProbability;
    std::vector<AliasSlot> mRows, mColumns;
    double mLuminanceIntegral = 0.0;
};

}  // namespace fovea::scene
