// Tangent frames for normal textures (core/scene/Tangents.h, GltfMesh.cpp): generated tangents
// are unit, perpendicular to the normal, follow the direction of increasing u and carry the
// handedness of v (mirrored UVs included); a glTF primitive with a normal texture gets them from
// its TANGENT attribute (rotated with the node, handedness flipped by a mirroring node) or
// generated; a TANGENT of zero length is an error naming the accessor; a non-numeric
// normalTexture.scale one naming its pointer. CPU only (sanitizer suite).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "core/image/ImageIO.h"
#include "core/scene/SceneLoader.h"
#include "core/scene/Tangents.h"
#include "core/util/Error.h"
#include "tests/unit/Base64.h"

using namespace fovea;
using namespace fovea::scene;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// A grid in the y = 0 plane, normal +Y, uv = (su * x, sv * z).
struct Grid {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<glm::uvec3> triangles;
};
Grid grid(float su, float sv, int n = 4) {
    Grid g;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            g.positions.emplace_back(float(i), 0.0f, float(j));
            g.normals.emplace_back(0.0f, 1.0f, 0.0f);
            g.uvs.emplace_back(su * float(i), sv * float(j));
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n) + 1,
                           d = c + 1;
            g.triangles.emplace_back(a, c, b);  // counter-clockwise seen from +Y
            g.triangles.emplace_back(b, c, d);
        }
    return g;
}

void expectFrame(const glm::vec4& t, const glm::vec3& tangent, float w) {
    EXPECT_NEAR(t.x, tangent.x, 1e-5f);
    EXPECT_NEAR(t.y, tangent.y, 1e-5f);
    EXPECT_NEAR(t.z, tangent.z, 1e-5f);
    EXPECT_EQ(t.w, w);
}

}  // namespace

// dP/du = +X: tangent +X; dP/dv = +Z while cross(N, T) = cross(+Y, +X) = -Z: w = -1.
TEST(Tangents, FollowTheUvGradientWithHandedness) {
    const Grid g = grid(0.5f, 0.25f);
    for (const glm::vec4& t : generateTangents(g.positions, g.normals, g.uvs, g.triangles))
        expectFrame(t, {1, 0, 0}, -1.0f);
    const Grid mirrored = grid(-0.5f, 0.25f);  // u decreasing along +X
    for (const glm::vec4& t :
         generateTangents(mirrored.positions, mirrored.normals, mirrored.uvs, mirrored.triangles))
        expectFrame(t, {-1, 0, 0}, 1.0f);
    const Grid flippedV = grid(0.5f, -0.25f);
    for (const glm::vec4& t :
         generateTangents(flippedV.positions, flippedV.normals, flippedV.uvs, flippedV.triangles))
        expectFrame(t, {1, 0, 0}, 1.0f);
}

// A smooth sphere: every tangent unit and perpendicular to its normal, along +u (east).
TEST(Tangents, AreOrthonormalOnACurvedSurface) {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    std::vector<glm::uvec3> triangles;
    const int rings = 12, segments = 24;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s <= segments; ++s) {
            const float theta = 3.14159265f * float(r) / rings;
            const float phi = 2.0f * 3.14159265f * float(s) / segments;
            const glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta),
                              std::sin(theta) * std::sin(phi));
            positions.push_back(p);
            normals.push_back(p);
            uvs.emplace_back(float(s) / segments, float(r) / rings);
        }
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const uint32_t a = uint32_t(r * (segments + 1) + s), b = a + 1,
                           c = a + uint32_t(segments) + 1, d = c + 1;
            triangles.emplace_back(a, b, c);
            triangles.emplace_back(b, d, c);
        }
    const auto tangents = generateTangents(positions, normals, uvs, triangles);
    for (size_t i = 0; i < tangents.size(); ++i) {
        const glm::vec3 t(tangents[i]);
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f) << i;
        EXPECT_NEAR(glm::dot(t, normals[i]), 0.0f, 1e-5f) << i;
        EXPECT_TRUE(tangents[i].w == 1.0f || tangents[i].w == -1.0f) << i;
        // Away from the poles the tangent is the direction of growing phi (u).
        const int r = int(i) / (segments + 1);
        if (r > 1 && r < rings - 1) {
            const glm::vec3 p = positions[i];
            const glm::vec3 east = glm::normalize(glm::vec3(-p.z, 0.0f, p.x));
            EXPECT_GT(glm::dot(t, east), 0.99f) << i;
        }
    }
}

// UVs without area: any unit tangent perpendicular to the normal, never NaN.
TEST(Tangents, DegenerateUvsGiveAPerpendicularFrame) {
    Grid g = grid(0.0f, 0.0f, 2);
    for (const glm::vec4& t : generateTangents(g.positions, g.normals, g.uvs, g.triangles)) {
        EXPECT_NEAR(glm::length(glm::vec3(t)), 1.0f, 1e-5f);
        EXPECT_NEAR(t.y, 0.0f, 1e-5f);
    }
    for (const glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(0.6f, 0.8f, 0)})
        EXPECT_NEAR(glm::dot(perpendicularTo(n), n), 0.0f, 1e-6f);
}

namespace {

// One quad (two triangles, indexed) with a normal texture, optionally TANGENT, under a node with
// `rotation` (quaternion xyzw) and `scale`.
fs::path writeQuad(const fs::path& dir, bool withTangents, const glm::vec4& tangent,
                   const std::vector<double>& rotation, const std::vector<double>& scale,
                   const json& normalTexture = json{{"index", 0}}) {
    const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 0, -1, 0, 0, -1};
    const std::vector<float> normals = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
    const std::vector<float> uvs = {0, 0, 1, 0, 1, 1, 0, 1};
    std::vector<float> tangents;
    for (int i = 0; i < 4; ++i)
        tangents.insert(tangents.end(), {tangent.x, tangent.y, tangent.z, tangent.w});
    const std::vector<uint16_t> indices = {0, 1, 2, 0, 2, 3};
    std::vector<uint8_t> bytes;
    auto append = [&](const void* data, size_t n) {
        const size_t offset = bytes.size();
        bytes.resize(offset + n);
        std::memcpy(bytes.data() + offset, data, n);
        return offset;
    };
    const size_t pOff = append(positions.data(), 48), nOff = append(normals.data(), 48),
                 uOff = append(uvs.data(), 32), tOff = append(tangents.data(), 64),
                 iOff = append(indices.data(), 12);
    // A 1x1 normal texture (0.5, 0.5, 1): the flat normal.
    image::ImageRGBA texel;
    texel.width = texel.height = 1;
    texel.pixels = {0.5f, 0.5f, 1.0f, 1.0f};
    image::writePng(dir / "normal.png", texel, image::PngEncoding::AsIs);
    json attributes = {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}};
    if (withTangents) attributes["TANGENT"] = 3;
    json gltf = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}, {"rotation", rotation}, {"scale", scale}}}},
        {"meshes",
         {{{"primitives", {{{"attributes", attributes}, {"indices", 4}, {"material", 0}}}}}}},
        {"materials", {{{"normalTexture", normalTexture}}}},
        {"textures", {{{"source", 0}}}},
        {"images", {{{"uri", "normal.png"}}}},
        {"buffers",
         {{{"byteLength", bytes.size()},
           {"uri", "data:application/octet-stream;base64," + test::base64(bytes)}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", pOff}, {"byteLength", 48}},
          {{"buffer", 0}, {"byteOffset", nOff}, {"byteLength", 48}},
          {{"buffer", 0}, {"byteOffset", uOff}, {"byteLength", 32}},
          {{"buffer", 0}, {"byteOffset", tOff}, {"byteLength", 64}},
          {{"buffer", 0}, {"byteOffset", iOff}, {"byteLength", 12}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", 4},
           {"type", "VEC3"},
           {"min", {0, 0, -1}},
           {"max", {1, 0, 0}}},
          {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
          {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
          {{"bufferView", 3}, {"componentType", 5126}, {"count", 4}, {"type", "VEC4"}},
          {{"bufferView", 4}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}}};
    const fs::path file = dir / "quad.gltf";
    std::ofstream(file) << gltf.dump(1);
    return file;
}

struct TempFolder {
    fs::path path =
        fs::temp_directory_path() / ("fovea_tangents_" + std::to_string(std::random_device{}()));
    TempFolder() { fs::create_directories(path); }
    ~TempFolder() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
};

const std::vector<double> kNoRotation = {0, 0, 0, 1}, kUnitScale = {1, 1, 1};

}  // namespace

TEST(TangentsGltf, GeneratedWithoutTangentAttribute) {
    TempFolder dir;
    const Scene s =
        loadScene(writeQuad(dir.path, false, glm::vec4(0.0f), kNoRotation, kUnitScale).string());
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_GE(s.materials[0].normalTexture, 0);
    ASSERT_EQ(s.mesh.tangents.size(), s.mesh.positions.size());
    // u grows along +X, v along -Z: T = +X, B = -Z = cross(+Y, +X) -> w = +1.
    for (const glm::vec4& t : s.mesh.tangents) expectFrame(t, {1, 0, 0}, 1.0f);
}

// TANGENT (0, 0, -1, -1) under a node rotated 90 degrees about +Y: xyz rotates to (-1, 0, 0);
// a mirroring scale (-1 in x) flips the handedness.
TEST(TangentsGltf, TangentAttributeFollowsTheNode) {
    TempFolder dir;
    const double h = std::sqrt(0.5);
    Scene s =
        loadScene(writeQuad(dir.path, true, {0, 0, -1, -1}, {0, h, 0, h}, kUnitScale).string());
    ASSERT_EQ(s.mesh.tangents.size(), 4u);
    for (const glm::vec4& t : s.mesh.tangents) expectFrame(t, {-1, 0, 0}, -1.0f);
    s = loadScene(writeQuad(dir.path, true, {1, 0, 0, 1}, kNoRotation, {-1, 1, 1}).string());
    for (const glm::vec4& t : s.mesh.tangents) expectFrame(t, {-1, 0, 0}, -1.0f);
}

TEST(TangentsGltf, BadTangentsAndScaleNameThePointer) {
    TempFolder dir;
    try {
        loadScene(writeQuad(dir.path, true, {0, 0, 0, 1}, kNoRotation, kUnitScale).string());
        FAIL() << "a zero TANGENT loaded";
    } catch (const InputError& e) {
        EXPECT_EQ(e.pointer(), "/accessors/3") << e.what();
        EXPECT_NE(std::string(e.what()).find("TANGENT of vertex 0"), std::string::npos) << e.what();
    }
    try {
        loadScene(writeQuad(dir.path, true, {1, 0, 0, 0.5f}, kNoRotation, kUnitScale).string());
        FAIL() << "a TANGENT with w = 0.5 loaded";
    } catch (const InputError& e) {
        EXPECT_EQ(e.pointer(), "/accessors/3") << e.what();
    }
    try {
        loadScene(writeQuad(dir.path, false, glm::vec4(0.0f), kNoRotation, kUnitScale,
                            json{{"index", 0}, {"scale", "large"}})
                      .string());
        FAIL() << "a string scale loaded";
    } catch (const InputError& e) {
        EXPECT_EQ(e.pointer(), "/materials/0/normalTexture/scale") << e.what();
    }
    const Scene scaled = loadScene(writeQuad(dir.path, false, glm::vec4(0.0f), kNoRotation,
                                             kUnitScale, json{{"index", 0}, {"scale", 0.25}})
                                       .string());
    EXPECT_EQ(scaled.materials[0].normalScale, 0.25f);
}
