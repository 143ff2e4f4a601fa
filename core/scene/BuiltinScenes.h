// Scenes built into fovea, selected as "builtin:<name>" (docs/scenes.md gives every number and
// its source):
//   cornell  the Cornell box from Cornell's own measurement data (millimetres, 38 triangles)
//   forest   the heavy procedural benchmark scene (~200k triangles, 80 point lights), seeded,
//            identical on every run
//   forest-10m  the same forest at 11.3M triangles (denser trees, finer tessellation), for
//            build, memory and traversal benchmarks at the scale of production scenes
//   plane    a diffuse plane under a large emissive quad: one bounce, known radiance
//   furnace  a closed box whose faces all emit Le and reflect rho: radiance Le / (1 - rho)
//   glossy   a roughness ramp (metal and dielectric spheres, roughness 0.05..1) over a glossy
//            floor, for the glossy/specular denoiser tests (issue 26)
#pragma once
#include <string>
#include <vector>

#include "core/scene/Scene.h"

namespace fovea::scene {

// `name` with or without the "builtin:" prefix. Unknown names: InputError with a did-you-mean
// and the list of built-in scenes.
Scene loadBuiltinScene(const std::string& name);

// "builtin:cornell", ... in a stable order.
std::vector<std::string> builtinSceneNames();

// The analytic scenes' parameters, for energy tests.
namespace builtin {

constexpr float kPlaneAlbedo = 0.5f;          // diffuse reflectance of the plane
constexpr float kPlaneEmission = 1.0f;        // Le of the emitter (grey)
constexpr float kPlaneHalfSize = 1.0f;        // the plane spans [-1, 1]^2 at y = 0
constexpr float kPlaneLightHeight = 1.0f;     // the emitter faces down at y = 1 ...
constexpr float kPlaneLightHalfSize = 50.0f;  // ... and spans [-50, 50]^2
// Radiance leaving the centre of the plane (one bounce; the emitter is black): albedo * Le * F,
// F = the form factor from a point to the parallel emitter square centred above it.
double planeCenterRadiance();

constexpr float kFurnaceAlbedo = 0.5f;    // rho of every face
constexpr float kFurnaceEmission = 0.5f;  // Le of every face
constexpr float kFurnaceHalfSize = 1.0f;  // the box is [-1, 1]^3, normals inwards
// Radiance anywhere inside after `bounces` reflections (Le * sum rho^k, k = 0..bounces); with
// bounces < 0 the infinite sum Le / (1 - rho) = 1.
double furnaceRadiance(int bounces = -1);

// builtin:glossy (BuiltinGlossy.cpp, docs/scenes.md): two rows of kGlossyColumns spheres, one
// material per sphere, roughness kGlossyRoughness[column]; row 0 (front, z > 0) metallic, row 1
// (back) dielectric.
constexpr int kGlossyColumns = 6;
constexpr float kGlossyRoughness[kGlossyColumns] = {0.05f, 0.2f, 0.4f, 0.6f, 0.8f, 1.0f};
constexpr float kGlossySphereRadius = 0.3f;      // resting on the floor (y = 0)
constexpr float kGlossySphereSpacing = 0.75f;    // between centres in x, centred on x = 0
constexpr float kGlossyRowZ[2] = {0.4f, -0.4f};  // front (metal), back (dielectric)
glm::vec3 glossySphereCenter(int row, int column);

}  // namespace builtin

// The forest generator (BuiltinForest.cpp). The default layout is builtin:forest (212,416
// triangles); builtin:forest-10m keeps the area, lights, rocks and crystals and raises the ground
// resolution, the tree density and every tree's tessellation to 11.3M triangles, the size of the
// scenes researchers bring (San Miguel, Bistro; issue 28), every triangle in the BVH (no
// instancing).
struct ForestLayout {
    std::string source = "builtin:forest";
    int groundCells = 128;  // per side: 2 * cells^2 ground triangles
    int treeGrid = 20;      // tree candidates per side (one per 160 m / treeGrid cell)
    int detail = 1;         // multiplies every tree's segments and rings
};
Scene buildForestScene(const ForestLayout& layout = {});
// The roughness ramp (BuiltinGlossy.cpp).
Scene buildGlossyScene();

}  // namespace fovea::scene
