// builtin:glossy, a roughness ramp for the glossy/specular denoiser tests (issue 26): two rows of
// six smooth spheres (front row metal, back row dielectric; roughness 0.05 .. 1 per column) on a
// glossy dielectric floor, in front of a wall of coloured tiles that gives the reflections
// structure, lit by one emissive quad above. Metres, y up; docs/scenes.md lists every number.
#include <cmath>
#include <numbers>
#include <string>

#include "core/scene/BuiltinGeometry.h"
#include "core/scene/BuiltinScenes.h"

namespace fovea::scene {

namespace {

using glm::vec2;
using glm::vec3;

constexpr float kFloorHalfWidth = 4.0f;  // the floor spans x in [-4, 4] ...
constexpr float kWallZ = -3.0f;          // ... and z in [-3, 5]: it meets the back wall
constexpr float kFloorDepth = 8.0f;
constexpr int kWallColumns = 8;  // 1 m tiles: 8 x 4 on the wall
constexpr int kWallRows = 4;
constexpr float kLightHeight = 3.5f;
constexpr float kLightHalfSize = 0.75f;  // 1.5 m x 1.5 m
constexpr float kLightRadiance = 10.0f;
constexpr int kSphereRings = 24;
constexpr int kSphereSegments = 48;

Material material(const std::string& name, const vec3& baseColor, float metallic, float roughness,
                  const vec3& emission = vec3(0.0f)) {
    Material m;
    m.name = name;
    m.baseColor = glm::vec4(baseColor, 1.0f);
    m.metallic = metallic;
    m.roughness = roughness;
    m.emissive = emission;
    return m;
}

uint32_t addMaterial(Scene& scene, Material m) {
    scene.materials.push_back(std::move(m));
    return uint32_t(scene.materials.size() - 1);
}

// A UV sphere with smooth per-vertex normals (radial, unit length), counter-clockwise seen from
// outside like MeshBuilder::triangle: `rings` bands from the north pole (+y) to the south pole,
// `segments` columns; the seam column is duplicated (u = 0 and u = 1) and each pole has one
// vertex per column, so no triangle is degenerate.
void addSphere(MeshBuilder& b, const vec3& center, float radius, int rings, int segments,
               uint32_t material) {
    const float pi = std::numbers::pi_v<float>;
    // The seam's u = 1 column takes phi = 0 exactly (not 2 pi) and the poles are exact, so
    // duplicated vertices share their positions bit for bit and the sphere stays watertight.
    auto point = [&](int r, float u) {
        float theta = pi * float(r) / float(rings), phi = u < 1.0f ? 2.0f * pi * u : 0.0f;
        vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
        if (r == 0 || r == rings) n = vec3(0.0f, r == 0 ? 1.0f : -1.0f, 0.0f);  // sin(pi_f) != 0
        return b.vertex(center + radius * n, n, vec2(u, float(r) / float(rings)));
    };
    // Rings 1 .. rings-1, segments + 1 vertices each.
    const uint32_t first = uint32_t(b.mesh().positions.size());
    for (int r = 1; r < rings; ++r) {
        for (int s = 0; s <= segments; ++s) point(r, float(s) / float(segments));
    }
    auto at = [&](int r, int s) { return first + uint32_t((r - 1) * (segments + 1) + s); };
    for (int s = 0; s < segments; ++s) {
        const float u = (float(s) + 0.5f) / float(segments);
        const uint32_t north = point(0, u), south = point(rings, u);
        b.indexed(north, at(1, s + 1), at(1, s), material);
        b.indexed(at(rings - 1, s), at(rings - 1, s + 1), south, material);
        for (int r = 1; r + 1 < rings; ++r) {
            // Ring r above ring r + 1; phi grows from +x towards +z.
            b.indexed(at(r, s), at(r + 1, s + 1), at(r + 1, s), material);
            b.indexed(at(r, s), at(r, s + 1), at(r + 1, s + 1), material);
        }
    }
}

}  // namespace

glm::vec3 builtin::glossySphereCenter(int row, int column) {
    return vec3((float(column) - 0.5f * float(kGlossyColumns - 1)) * kGlossySphereSpacing,
                kGlossySphereRadius, kGlossyRowZ[row]);
}

Scene buildGlossyScene() {
    using namespace builtin;
    Scene scene;
    scene.source = "builtin:glossy";
    MeshBuilder b(scene.mesh);

    // Floor: a glossy dielectric (grey 0.3, roughness 0.1) that mirrors what stands on it.
    const uint32_t floor = addMaterial(scene, material("floor", vec3(0.3f), 0.0f, 0.1f));
    const float w = kFloorHalfWidth, z0 = kWallZ, z1 = kWallZ + kFloorDepth;
    b.quadFacing({-w, 0, z0}, {w, 0, z0}, {w, 0, z1}, {-w, 0, z1}, floor, vec3(0, 1, 0));

    // Back wall at z = -3 facing +z: 8 x 4 diffuse tiles of 1 m in five colours; the colour of
    // tile (i, j) is (i + 3 j) mod 5, so no two neighbours (across an edge) share one.
    const vec3 palette[5] = {{0.8f, 0.8f, 0.8f},
                             {0.7f, 0.1f, 0.1f},
                             {0.1f, 0.6f, 0.15f},
                             {0.1f, 0.2f, 0.7f},
                             {0.8f, 0.7f, 0.1f}};
    const char* paletteNames[5] = {"wall_white", "wall_red", "wall_green", "wall_blue",
                                   "wall_yellow"};
    uint32_t wall[5];
    for (int c = 0; c < 5; ++c)
        wall[c] = addMaterial(scene, material(paletteNames[c], palette[c], 0.0f, 1.0f));
    for (int j = 0; j < kWallRows; ++j) {
        for (int i = 0; i < kWallColumns; ++i) {
            const float x0 = -w + float(i), x1 = x0 + 1.0f, y0 = float(j), y1 = y0 + 1.0f;
            const vec3 front(0.5f * (x0 + x1), 0.5f * (y0 + y1), 0.0f);
            b.quadFacing({x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0},
                         wall[(i + 3 * j) % 5], front);
        }
    }

    // The spheres: front row metal (gold), back row dielectric (dark red); roughness per column.
    const char* roughnessNames[kGlossyColumns] = {"0.05", "0.2", "0.4", "0.6", "0.8", "1.0"};
    for (int row = 0; row < 2; ++row) {
        for (int column = 0; column < kGlossyColumns; ++column) {
            const bool metal = row == 0;
            const uint32_t m = addMaterial(
                scene,
                material(std::string(metal ? "metal_r" : "dielectric_r") + roughnessNames[column],
                         metal ? vec3(1.0f, 0.77f, 0.34f) : vec3(0.6f, 0.1f, 0.1f),
                         metal ? 1.0f : 0.0f, kGlossyRoughness[column]));
            addSphere(b, glossySphereCenter(row, column), kGlossySphereRadius, kSphereRings,
                      kSphereSegments, m);
        }
    }

    // The light: a 1.5 m square at y = 3.5 above the spheres, facing down (as Cornell's light:
    // diffuse reflectance 0.78 plus emission).
    const uint32_t light =
        addMaterial(scene, material("light", vec3(0.78f), 0.0f, 1.0f, vec3(kLightRadiance)));
    const float l = kLightHalfSize, h = kLightHeight;
    b.quadFacing({-l, h, -l}, {l, h, -l}, {l, h, l}, {-l, h, l}, light, vec3(0.0f));

    CameraDesc camera;
    camera.name = "glossy";
    camera.position = vec3(0.0f, 1.4f, 4.0f);
    camera.target = vec3(0.0f, 0.35f, 0.0f);
    camera.up = vec3(0.0f, 1.0f, 0.0f);
    camera.yfov = 0.8f;
    camera.znear = 0.01f;
    scene.cameras.push_back(camera);
    for (const vec3& p : scene.mesh.positions) scene.bounds.grow(p);
    return scene;
}

}  // namespace fovea::scene
