#pragma once
// Pre-integrated specular reflectance of PathTrace's GGX lobe (shaders/pathtrace/brdf.glsl: GGX D,
// height-correlated Smith G2, Schlick F, alpha = max(roughness^2, 2e-3)): the fraction of light
// from a white furnace that the specular lobe alone reflects towards wo,
//
//   E(F0, roughness, NoV) = integral of f_spec(wo, wi) cos(theta_i) dwi = F0 * scale + bias,
//
// linear in F0 because Schlick's F is (scale: the (1 - (1 - VoH)^5) part, bias: the (1 - VoH)^5
// part). Specular radiance is demodulated by E (issue 26, seed 004 "Cooking specular denoiser":
// the specular signal is divided by its pre-integrated BRDF before filtering, as NRD does), so
// the table is what the shaders and the CPU oracles share. The table is baked into the build
// (SpecularAlbedoTable.inc, written by specularAlbedoTableSource(); a test checks that it matches
// specularAlbedoTable() and rewrites it with FOVEA_UPDATE_TABLES=1) and uploaded by the passes
// that need it as the storage buffer `specular_albedo_table` (shaders/common/specular_albedo.glsl).
// Not a GLSL constant array: lavapipe 22.3 compiles a dynamically indexed 1024-entry constant for
// minutes.
#include <glm/vec2.hpp>
#include <string>
#include <vector>

namespace fovea::shading {

// Table resolution: entries at NoV = i / (kSpecularAlbedoSize - 1) (NoV 0 evaluated at the
// shader's floor kSpecularMinCos) and roughness = j / (kSpecularAlbedoSize - 1).
constexpr int kSpecularAlbedoSize = 32;
constexpr double kSpecularMinAlpha = 2e-3;  // brdf.glsl kMinAlpha
constexpr double kSpecularMinCos = 1e-4;    // brdf.glsl kMinCos

// {scale, bias} at one point by stratified VNDF importance sampling (Heitz 2018: the weight of
// a visible-normal sample is F G2 / G1(wo)) over n x n strata. Deterministic.
glm::dvec2 integrateSpecularAlbedo(double nov, double roughness, int n = 128);

// The same integral by midpoint quadrature of the BRDF formula over the hemisphere (theta x phi
// cells): independent of the sampling code, accurate for roughness >= ~0.3 (narrower lobes fall
// between the cells).
glm::dvec2 integrateSpecularAlbedoQuadrature(double nov, double roughness, int thetaSteps,
                                             int phiSteps);

// kSpecularAlbedoSize^2 entries, row j (roughness) major, column i (NoV), integrated now (about
// a second): what the baked table must equal.
std::vector<glm::vec2> specularAlbedoTable();

// The same entries as baked into the build (SpecularAlbedoTable.inc): free to call.
const std::vector<glm::vec2>& bakedSpecularAlbedoTable();

// Bilinear lookup between the entries, NoV and roughness clamped to [0, 1]: what
// specularAlbedo() in shaders/common/specular_albedo.glsl computes.
glm::dvec2 lookupSpecularAlbedo(const std::vector<glm::vec2>& table, double nov, double roughness);

// The text of core/shading/SpecularAlbedoTable.inc for `table`.
std::string specularAlbedoTableSource(const std::vector<glm::vec2>& table);

}  // namespace fovea::shading
