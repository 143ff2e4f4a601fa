// builtin:glossy (core/scene/BuiltinGlossy.cpp): the roughness ramp of the glossy denoiser tests
// (issue 26) and its camera path graphs/cameras/glossy_truck.json (CPU only).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include "core/scene/BuiltinScenes.h"
#include "core/scene/CameraPath.h"
#include "core/scene/SceneFeatures.h"

using namespace fovea;
using namespace fovea::scene;

namespace {

const std::filesystem::path kTruck = std::filesystem::path(FOVEA_TEST_DIR).parent_path() /
                                     "graphs" / "cameras" / "glossy_truck.json";

// The material named `name`, or -1.
int findMaterial(const Scene& s, const std::string& name) {
    for (size_t i = 0; i < s.materials.size(); ++i)
        if (s.materials[i].name == name) return int(i);
    return -1;
}

std::string sphereName(int row, int column) {
    const char* r[builtin::kGlossyColumns] = {"0.05", "0.2", "0.4", "0.6", "0.8", "1.0"};
    return std::string(row == 0 ? "metal_r" : "dielectric_r") + r[column];
}

}  // namespace

TEST(BuiltinGlossy, IsListedAndLoads) {
    auto names = builtinSceneNames();
    EXPECT_NE(std::find(names.begin(), names.end(), "builtin:glossy"), names.end());
    Scene s = loadBuiltinScene("builtin:glossy");
    EXPECT_EQ(s.source, "builtin:glossy");
    EXPECT_EQ(loadBuiltinScene("glossy").mesh.positions, s.mesh.positions);
    EXPECT_EQ(s.mesh.normals.size(), s.mesh.positions.size());
    EXPECT_EQ(s.mesh.uvs.size(), s.mesh.positions.size());
    EXPECT_EQ(s.mesh.materialIds.size(), s.mesh.triangles.size());
    for (const glm::uvec3& t : s.mesh.triangles)
        for (int k = 0; k < 3; ++k) ASSERT_LT(t[k], s.mesh.positions.size());
    for (uint32_t m : s.mesh.materialIds) ASSERT_LT(m, s.materials.size());
    EXPECT_EQ(s.features(), uint32_t(kSceneGeometry | kSceneEmissive));
    // Pinned (docs/scenes.md): floor 2, wall 8 x 4 tiles x 2, light 2, and 12 spheres of
    // 24 rings x 48 segments (2 x 48 pole triangles + 22 bands x 96).
    EXPECT_EQ(s.mesh.triangleCount(), 2u + 64u + 2u + 12u * (2u * 48u + 22u * 96u));
    EXPECT_TRUE(s.lights.empty());
    // Floor 8 x 8 m at y = 0, wall at z = -3, light at y = 3.5.
    EXPECT_FLOAT_EQ(s.bounds.min.y, 0.0f);
    EXPECT_FLOAT_EQ(s.bounds.max.y, 4.0f);
    EXPECT_FLOAT_EQ(s.bounds.min.z, -3.0f);
    EXPECT_FLOAT_EQ(s.bounds.max.z, 5.0f);
    EXPECT_FLOAT_EQ(s.bounds.max.x - s.bounds.min.x, 8.0f);

    ASSERT_EQ(s.cameras.size(), 1u);
    EXPECT_EQ(s.cameras[0].position, glm::vec3(0.0f, 1.4f, 4.0f));
    EXPECT_EQ(s.cameras[0].target, glm::vec3(0.0f, 0.35f, 0.0f));
    EXPECT_FLOAT_EQ(s.cameras[0].yfov, 0.8f);
    EXPECT_FLOAT_EQ(s.cameras[0].znear, 0.01f);
}

TEST(BuiltinGlossy, MaterialsRampRoughness) {
    Scene s = loadBuiltinScene("builtin:glossy");
    int spheres = 0;
    for (const Material& m : s.materials)
        spheres += m.name.rfind("metal_r", 0) == 0 || m.name.rfind("dielectric_r", 0) == 0;
    EXPECT_EQ(spheres, 12);
    for (int row = 0; row < 2; ++row) {
        for (int column = 0; column < builtin::kGlossyColumns; ++column) {
            int id = findMaterial(s, sphereName(row, column));
            ASSERT_GE(id, 0) << sphereName(row, column);
            const Material& m = s.materials[size_t(id)];
            EXPECT_FLOAT_EQ(m.roughness, builtin::kGlossyRoughness[column]) << m.name;
            EXPECT_FLOAT_EQ(m.metallic, row == 0 ? 1.0f : 0.0f) << m.name;
            EXPECT_EQ(glm::vec3(m.baseColor),
                      row == 0 ? glm::vec3(1.0f, 0.77f, 0.34f) : glm::vec3(0.6f, 0.1f, 0.1f))
                << m.name;
            EXPECT_FALSE(m.isEmissive()) << m.name;
        }
    }
    const float ramp[] = {0.05f, 0.2f, 0.4f, 0.6f, 0.8f, 1.0f};
    for (int c = 0; c < builtin::kGlossyColumns; ++c)
        EXPECT_FLOAT_EQ(builtin::kGlossyRoughness[c], ramp[c]);

    int floor = findMaterial(s, "floor");
    ASSERT_GE(floor, 0);
    EXPECT_FLOAT_EQ(s.materials[size_t(floor)].metallic, 0.0f);
    EXPECT_FLOAT_EQ(s.materials[size_t(floor)].roughness, 0.1f);
    int light = findMaterial(s, "light");
    ASSERT_GE(light, 0);
    EXPECT_EQ(s.materials[size_t(light)].emissive, glm::vec3(10.0f));
    // The light is the only emitter, and every emissive triangle faces down.
    for (size_t t = 0; t < s.mesh.triangles.size(); ++t) {
        const Material& m = s.materials[s.mesh.materialIds[t]];
        EXPECT_EQ(m.isEmissive(), int(s.mesh.materialIds[t]) == light) << m.name;
        if (m.isEmissive()) {
            EXPECT_FLOAT_EQ(s.mesh.positions[s.mesh.triangles[t].x].y, 3.5f);
            EXPECT_LT(s.mesh.normals[s.mesh.triangles[t].x].y, -0.99f);
        }
    }
    // The wall is diffuse and coloured: several materials, all of roughness 1.
    int wallMaterials = 0;
    for (const Material& m : s.materials) {
        if (m.name.rfind("wall_", 0) != 0) continue;
        ++wallMaterials;
        EXPECT_FLOAT_EQ(m.roughness, 1.0f) << m.name;
        EXPECT_FLOAT_EQ(m.metallic, 0.0f) << m.name;
    }
    EXPECT_GE(wallMaterials, 3);
}

TEST(BuiltinGlossy, SphereNormalsAreSmoothAndOutward) {
    Scene s = loadBuiltinScene("builtin:glossy");
    const TriangleMesh& mesh = s.mesh;
    for (int row = 0; row < 2; ++row) {
        for (int column = 0; column < builtin::kGlossyColumns; ++column) {
            const std::string name = sphereName(row, column);
            const uint32_t id = uint32_t(findMaterial(s, name));
            const glm::vec3 c = builtin::glossySphereCenter(row, column);
            EXPECT_FLOAT_EQ(c.y, builtin::kGlossySphereRadius) << name;  // resting on the floor
            EXPECT_FLOAT_EQ(c.z, row == 0 ? 0.4f : -0.4f) << name;
            EXPECT_NEAR(c.x, (float(column) - 2.5f) * 0.75f, 1e-6f) << name;
            std::map<uint32_t, bool> vertices;
            size_t triangles = 0;
            for (size_t t = 0; t < mesh.triangles.size(); ++t) {
                if (mesh.materialIds[t] != id) continue;
                ++triangles;
                const glm::uvec3 tri = mesh.triangles[t];
                for (int k = 0; k < 3; ++k) vertices[tri[k]] = true;
                // Winding: the geometric normal (counter-clockwise front, as MeshBuilder's
                // quads) agrees with the vertex normals and points out of the sphere.
                const glm::vec3 a = mesh.positions[tri.x], b = mesh.positions[tri.y],
                                c2 = mesh.positions[tri.z];
                const glm::vec3 g = glm::cross(b - a, c2 - a);
                ASSERT_GT(glm::length(g), 0.0f) << name << " triangle " << t;
                const glm::vec3 centroid = (a + b + c2) / 3.0f;
                EXPECT_GT(glm::dot(glm::normalize(g), glm::normalize(centroid - c)), 0.9f)
                    << name << " triangle " << t;
                for (int k = 0; k < 3; ++k)
                    EXPECT_GT(glm::dot(g, mesh.normals[tri[k]]), 0.0f) << name << " triangle " << t;
            }
            EXPECT_GE(triangles, 2u * 24u * 16u) << name;  // smooth enough for a glossy lobe
            glm::vec3 lo(1e9f), hi(-1e9f);
            for (const auto& [v, used] : vertices) {
                const glm::vec3 p = mesh.positions[v], n = mesh.normals[v];
                EXPECT_NEAR(glm::length(p - c), builtin::kGlossySphereRadius, 1e-5f) << name;
                EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f) << name << " vertex " << v;
                EXPECT_GT(glm::dot(n, glm::normalize(p - c)), 0.99f) << name << " vertex " << v;
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
            // Watertight: every edge is shared by exactly two triangles, comparing positions
            // (the seam and pole vertices are duplicated for their uvs).
            std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> edges;
            auto key = [](glm::vec3 p) { return std::array<float, 3>{p.x, p.y, p.z}; };
            for (size_t t = 0; t < mesh.triangles.size(); ++t) {
                if (mesh.materialIds[t] != id) continue;
                for (int e = 0; e < 3; ++e) {
                    auto a = key(mesh.positions[mesh.triangles[t][e]]);
                    auto b = key(mesh.positions[mesh.triangles[t][(e + 1) % 3]]);
                    edges[{std::min(a, b), std::max(a, b)}]++;
                }
            }
            for (const auto& [edge, count] : edges) ASSERT_EQ(count, 2) << name;
            // The vertices span the whole sphere around its centre.
            EXPECT_LT(glm::length(0.5f * (lo + hi) - c), 1e-5f) << name;
            EXPECT_NEAR(hi.y - lo.y, 2.0f * builtin::kGlossySphereRadius, 1e-5f) << name;
        }
    }
}

TEST(BuiltinGlossy, TruckPathParses) {
    CameraPath path = CameraPath::load(kTruck);
    ASSERT_GE(path.keys().size(), 2u);
    EXPECT_GE(path.length(), 16u);
    EXPECT_FALSE(path.loops());
    const uint64_t last = path.keys().back().frame;
    float previousX = -1e9f;
    for (uint64_t f = 0; f <= last; ++f) {
        CameraSample sample = path.at(f);
        EXPECT_FALSE(sample.cut) << "frame " << f;
        EXPECT_NEAR(sample.camera.position.y, 1.4f, 1e-5f) << "frame " << f;
        EXPECT_NEAR(sample.camera.position.z, 4.0f, 1e-5f) << "frame " << f;
        EXPECT_GT(sample.camera.position.x, previousX) << "frame " << f;  // one way, sideways
        previousX = sample.camera.position.x;
        EXPECT_LT(glm::distance(sample.camera.target, glm::vec3(0.0f, 0.35f, 0.0f)), 1e-5f);
        EXPECT_NEAR(sample.camera.yfov, 0.8f, 1e-3f) << "frame " << f;
    }
    EXPECT_NEAR(path.at(0).camera.position.x, -0.6f, 1e-5f);
    EXPECT_NEAR(path.at(last).camera.position.x, 0.6f, 1e-5f);
}
