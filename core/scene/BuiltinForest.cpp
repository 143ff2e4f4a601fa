// builtin:forest, the heavy procedural benchmark scene "in the spirit of Peres' Forest": rolling
// ground, ~360 trees (broadleaf and conifer), rocks, glowing crystals and 80 warm point lights in
// a 160 m x 160 m square, ~220k triangles. Everything comes from one fixed seed through a
// self-contained generator (SplitMix64), not <random>: the standard distributions may differ
// between library versions, and the benchmark must draw the same triangles everywhere.
#include <array>
#include <cmath>
#include <numbers>

#include "core/scene/BuiltinGeometry.h"
#include "core/scene/BuiltinScenes.h"

namespace fovea::scene {

namespace {

using glm::vec2;
using glm::vec3;

constexpr uint64_t kForestSeed = 0x5EED'F0E5'7000'0001ull;
constexpr float kHalfExtent = 80.0f;  // metres; the ground spans [-80, 80]^2
constexpr int kRocks = 200;
constexpr int kCrystals = 40;
constexpr int kLights = 80;
constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

class Rng {
public:
    explicit Rng(uint64_t seed) : mState(seed) {}
    uint64_t next() {
        uint64_t z = (mState += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    float uniform() { return float(next() >> 40) * (1.0f / 16777216.0f); }  // [0, 1)
    float range(float lo, float hi) { return lo + (hi - lo) * uniform(); }

private:
    uint64_t mState;
};

// Smooth rolling terrain (metres): a few incommensurate waves, no noise tables needed.
float groundHeight(float x, float z) {
    return 1.6f * std::sin(0.045f * x + 0.3f) * std::cos(0.037f * z) +
           0.7f * std::sin(0.11f * x + 1.7f) * std::sin(0.13f * z + 0.4f) +
           0.25f * std::cos(0.31f * x - 0.2f * z);
}

vec3 groundNormal(float x, float z) {
    const float e = 0.05f;
    float dx = (groundHeight(x + e, z) - groundHeight(x - e, z)) / (2.0f * e);
    float dz = (groundHeight(x, z + e) - groundHeight(x, z - e)) / (2.0f * e);
    return glm::normalize(vec3(-dx, 1.0f, -dz));
}

void addGround(MeshBuilder& b, uint32_t material, int cells) {
    const int n = cells;
    const float step = 2.0f * kHalfExtent / float(n);
    uint32_t first = uint32_t(b.mesh().positions.size());
    for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
            float x = -kHalfExtent + step * float(i), z = -kHalfExtent + step * float(j);
            b.vertex({x, groundHeight(x, z), z}, groundNormal(x, z),
                     vec2(float(i), float(j)) / 8.0f);
        }
    }
    auto at = [&](int i, int j) { return first + uint32_t(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            // Counter-clockwise seen from above (+y).
            b.indexed(at(i, j), at(i, j + 1), at(i + 1, j + 1), material);
            b.indexed(at(i, j), at(i + 1, j + 1), at(i + 1, j), material);
        }
    }
}

// A ring-stacked surface of revolution around `base` (+y axis): radius(t) for t in [0, 1] over
// `height`; `rings` + 1 vertex rings of `segments` vertices, closed by fans at both ends.
void addRevolution(MeshBuilder& b, const vec3& base, float height, int segments, int rings,
                   uint32_t material, float (*radius)(float, float), float shape, Rng& rng,
                   float jitter) {
    uint32_t first = uint32_t(b.mesh().positions.size());
    for (int r = 0; r <= rings; ++r) {
        float t = float(r) / float(rings);
        for (int s = 0; s < segments; ++s) {
            float a = kTwoPi * float(s) / float(segments);
            float rad = radius(t, shape) * (1.0f + jitter * (rng.uniform() - 0.5f));
            vec3 dir(std::cos(a), 0.0f, std::sin(a));
            vec3 p = base + vec3(0.0f, t * height, 0.0f) + dir * rad;
            // Slope-aware normal of the profile (outwards and up where the radius shrinks).
            float dt = 1e-3f;
            float slope =
                (radius(std::min(t + dt, 1.0f), shape) - radius(std::max(t - dt, 0.0f), shape)) /
                (height * (std::min(t + dt, 1.0f) - std::max(t - dt, 0.0f)));
            b.vertex(p, dir - vec3(0.0f, slope, 0.0f));
        }
    }
    auto at = [&](int r, int s) { return first + uint32_t(r * segments + (s % segments)); };
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            b.indexed(at(r, s), at(r + 1, s), at(r + 1, s + 1), material);
            b.indexed(at(r, s), at(r + 1, s + 1), at(r, s + 1), material);
        }
    }
    uint32_t bottom = b.vertex(base, vec3(0.0f, -1.0f, 0.0f));
    uint32_t top = b.vertex(base + vec3(0.0f, height, 0.0f), vec3(0.0f, 1.0f, 0.0f));
    for (int s = 0; s < segments; ++s) {
        // The ring runs counter-clockwise seen from below (+x towards +z).
        b.indexed(bottom, at(0, s), at(0, s + 1), material);
        b.indexed(top, at(rings, s + 1), at(rings, s), material);
    }
}

float trunkRadius(float t, float r) {
    return r * (1.0f - 0.35f * t);
}
float coneRadius(float t, float r) {
    return r * (1.0f - t) + 0.02f;
}
float crownRadius(float t, float r) {
    return r * std::sqrt(std::max(0.0f, std::sin(std::numbers::pi_v<float> * t))) + 0.05f;
}

void addTree(MeshBuilder& b, const vec3& root, Rng& rng, uint32_t bark, uint32_t leavesA,
             uint32_t leavesB, uint32_t needles, int detail) {
    const int d = detail;  // segments and rings of every surface of revolution are multiplied
    bool conifer = rng.uniform() < 0.45f;
    float trunkHeight = conifer ? rng.range(2.0f, 3.5f) : rng.range(3.0f, 5.5f);
    float trunk = rng.range(0.18f, 0.35f);
    addRevolution(b, root - vec3(0.0f, 0.3f, 0.0f), trunkHeight + 0.3f, 10 * d, 3 * d, bark,
                  &trunkRadius, trunk, rng, 0.1f);
    if (conifer) {
        // Four stacked cones, each smaller and higher.
        float radius = rng.range(2.0f, 3.2f), y = trunkHeight * 0.6f;
        for (int i = 0; i < 4; ++i) {
            float h = radius * 1.6f;
            addRevolution(b, root + vec3(0.0f, y, 0.0f), h, 16 * d, 2 * d, needles, &coneRadius,
                          radius, rng, 0.15f);
            y += h * 0.55f;
            radius *= 0.75f;
        }
    } else {
        float radius = rng.range(2.2f, 3.6f);
        addRevolution(b, root + vec3(0.0f, trunkHeight * 0.75f, 0.0f), radius * 2.2f, 16 * d,
                      10 * d, rng.uniform() < 0.5f ? leavesA : leavesB, &crownRadius, radius, rng,
                      0.25f);
    }
}

// A lumpy icosahedron subdivided once (80 triangles), half sunk into the ground.
void addRock(MeshBuilder& b, const vec3& centre, float size, Rng& rng, uint32_t material) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    const vec3 v[12] = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                        {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                          {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                          {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                          {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    vec3 squash(rng.range(0.8f, 1.3f), rng.range(0.5f, 0.8f), rng.range(0.8f, 1.3f));
    float phase = rng.range(0.0f, kTwoPi);
    auto place = [&](vec3 d) {
        d = glm::normalize(d);
        float bump = 1.0f + 0.12f * std::sin(5.0f * d.x + phase) * std::cos(4.0f * d.z + phase);
        return centre + d * squash * size * bump;
    };
    for (const auto& face : f) {
        vec3 a = v[face[0]], c = v[face[1]], d = v[face[2]];
        vec3 ab = a + c, bc = c + d, ca = d + a;  // midpoints (normalised in place())
        for (const auto& tri : {std::array<vec3, 3>{a, ab, ca}, std::array<vec3, 3>{ab, c, bc},
                                std::array<vec3, 3>{ca, bc, d}, std::array<vec3, 3>{ab, bc, ca}}) {
            b.triangleFacing(place(tri[0]), place(tri[1]), place(tri[2]), material,
                             centre + 4.0f * size * glm::normalize(tri[0] + tri[1] + tri[2]));
        }
    }
}

// An elongated octahedron (8 triangles) standing on the ground.
void addCrystal(MeshBuilder& b, const vec3& base, float size, uint32_t material) {
    vec3 top = base + vec3(0.0f, 3.0f * size, 0.0f), mid = base + vec3(0.0f, 1.2f * size, 0.0f);
    vec3 ring[4] = {mid + vec3(size, 0, 0), mid + vec3(0, 0, size), mid - vec3(size, 0, 0),
                    mid - vec3(0, 0, size)};
    for (int i = 0; i < 4; ++i) {
        const vec3& p = ring[i];
        const vec3& q = ring[(i + 1) % 4];
        b.triangleFacing(p, q, top, material, mid + 10.0f * (p + q - 2.0f * mid));
        b.triangleFacing(p, q, base, material, mid + 10.0f * (p + q - 2.0f * mid));
    }
}

}  // namespace

Scene buildForestScene(const ForestLayout& layout) {
    Scene scene;
    scene.source = layout.source;
    auto material = [&](const char* name, vec3 albedo, vec3 emission = vec3(0.0f)) {
        Material m;
        m.name = name;
        m.baseColor = glm::vec4(albedo, 1.0f);
        m.emissive = emission;
        m.metallic = 0.0f;
        m.roughness = 0.9f;
        scene.materials.push_back(m);
        return uint32_t(scene.materials.size() - 1);
    };
    uint32_t ground = material("ground", {0.20f, 0.26f, 0.11f});
    uint32_t bark = material("bark", {0.28f, 0.19f, 0.12f});
    uint32_t leavesA = material("leaves", {0.13f, 0.34f, 0.08f});
    uint32_t leavesB = material("leaves-autumn", {0.42f, 0.30f, 0.07f});
    uint32_t needles = material("needles", {0.07f, 0.22f, 0.10f});
    uint32_t rock = material("rock", {0.38f, 0.37f, 0.35f});
    uint32_t crystal = material("crystal", {0.2f, 0.5f, 0.9f}, {0.6f, 2.4f, 6.0f});

    Rng rng(kForestSeed);
    MeshBuilder b(scene.mesh);
    addGround(b, ground, layout.groundCells);
    const float cell = 2.0f * kHalfExtent / float(layout.treeGrid);
    for (int j = 0; j < layout.treeGrid; ++j) {
        for (int i = 0; i < layout.treeGrid; ++i) {
            if (rng.uniform() > 0.9f) continue;  // a few clearings
            float x = -kHalfExtent + cell * (float(i) + rng.range(0.2f, 0.8f));
            float z = -kHalfExtent + cell * (float(j) + rng.range(0.2f, 0.8f));
            addTree(b, {x, groundHeight(x, z), z}, rng, bark, leavesA, leavesB, needles,
                    layout.detail);
        }
    }
    for (int r = 0; r < kRocks; ++r) {
        float x = rng.range(-kHalfExtent, kHalfExtent), z = rng.range(-kHalfExtent, kHalfExtent);
        float size = rng.range(0.3f, 1.4f);
        addRock(b, {x, groundHeight(x, z) + 0.1f * size, z}, size, rng, rock);
    }
    for (int c = 0; c < kCrystals; ++c) {
        float x = rng.range(-kHalfExtent, kHalfExtent), z = rng.range(-kHalfExtent, kHalfExtent);
        addCrystal(b, {x, groundHeight(x, z), z}, rng.range(0.1f, 0.25f), crystal);
    }
    for (int l = 0; l < kLights; ++l) {
        Light light;
        light.name = "lantern " + std::to_string(l);
        float x = rng.range(-kHalfExtent, kHalfExtent), z = rng.range(-kHalfExtent, kHalfExtent);
        light.position = vec3(x, groundHeight(x, z) + rng.range(0.6f, 3.0f), z);
        light.color = vec3(1.0f, rng.range(0.55f, 0.8f), rng.range(0.25f, 0.45f));  // warm
        light.intensity = rng.range(8.0f, 40.0f);                                   // candela
        scene.lights.push_back(light);
    }
    CameraDesc camera;
    camera.name = "forest";
    camera.position = vec3(0.0f, groundHeight(0.0f, 70.0f) + 1.7f, 70.0f);
    camera.target = vec3(0.0f, groundHeight(0.0f, 0.0f) + 3.0f, 0.0f);
    camera.yfov = 0.9f;
    camera.znear = 0.05f;
    scene.cameras.push_back(camera);
    for (const vec3& p : scene.mesh.positions) scene.bounds.grow(p);
    return scene;
}

}  // namespace fovea::scene
