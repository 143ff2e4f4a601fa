// glTF alphaMode / alphaCutoff (glTF 2.0 §3.9.4) on small synthetic files: the loader keeps the
// mode and the cutoff (default 0.5), a MASK with cutoff 0 counts as opaque, the scene reports the
// alpha feature only for materials a triangle uses, and the validator rejects a negative or
// non-finite alphaCutoff naming /materials/<i>/alphaCutoff. CPU only (sanitizer suite).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/graph/Pass.h"
#include "core/scene/SceneLoader.h"
#include "core/util/Error.h"
#include "tests/unit/Base64.h"
#include "tests/unit/SceneLoadTestUtil.h"

namespace fs = std::filesystem;
using namespace fovea;
using namespace fovea::scene;
using namespace fovea::scenetest;
using nlohmann::json;

namespace {

// One unit quad (4 float positions, 6 uint16 indices) drawn once per entry of `materials`, each
// primitive with its own material; the materials are spliced in as JSON text so tests can write
// numbers JSON writers refuse (1e999).
std::string quadGltf(const std::vector<std::string>& materials, size_t drawn) {
    std::vector<uint8_t> bytes;
    const float positions[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
    bytes.resize(sizeof positions + sizeof indices);
    std::memcpy(bytes.data(), positions, sizeof positions);
    std::memcpy(bytes.data() + sizeof positions, indices, sizeof indices);
    json primitives = json::array();
    for (size_t m = 0; m < drawn; ++m)
        primitives.push_back({{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", m}});
    json gltf = {{"asset", {{"version", "2.0"}}},
                 {"scene", 0},
                 {"scenes", {{{"nodes", {0}}}}},
                 {"nodes", {{{"mesh", 0}}}},
                 {"meshes", {{{"primitives", primitives}}}},
                 {"accessors",
                  {{{"bufferView", 0},
                    {"componentType", 5126},
                    {"count", 4},
                    {"type", "VEC3"},
                    {"min", {0, 0, 0}},
                    {"max", {1, 1, 0}}},
                   {{"bufferView", 1}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
                 {"bufferViews",
                  {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
                   {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 12}}}},
                 {"buffers",
                  {{{"byteLength", bytes.size()},
                    {"uri", "data:application/octet-stream;base64," + test::base64(bytes)}}}},
                 {"materials", json::array()}};
    std::string text = gltf.dump();
    std::string list;
    for (const std::string& m : materials) list += (list.empty() ? "" : ",") + m;
    const std::string empty = "\"materials\":[]";
    return text.replace(text.find(empty), empty.size(), "\"materials\":[" + list + "]");
}

class SceneGltfAlpha : public ::testing::Test {
protected:
    void SetUp() override {
        mDir = fs::temp_directory_path() / ("fovea-alpha-test-" + std::to_string(::getpid()));
        fs::create_directories(mDir);
    }
    void TearDown() override { fs::remove_all(mDir); }
    fs::path write(const std::string& text) {
        fs::path path = mDir / "alpha.gltf";
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }
    fs::path mDir;
};

TEST_F(SceneGltfAlpha, ModesAndCutoffsAreKept) {
    const std::vector<std::string> materials = {R"({})",
                                                R"({"alphaMode": "MASK"})",
                                                R"({"alphaMode": "MASK", "alphaCutoff": 0.25})",
                                                R"({"alphaMode": "BLEND", "alphaCutoff": 0.9})",
                                                R"({"alphaMode": "MASK", "alphaCutoff": 0})",
                                                R"({"alphaMode": "MASK", "alphaCutoff": 7})",
                                                R"({"alphaMode": "OPAQUE", "alphaCutoff": 0.75})"};
    Scene s = loadScene(write(quadGltf(materials, materials.size())).string());
    ASSERT_EQ(s.materials.size(), materials.size());
    auto material = [&](size_t primitive) -> const Material& {
        return s.materials.at(s.mesh.materialIds.at(2 * primitive));  // two triangles each
    };
    EXPECT_EQ(material(0).alphaMode, AlphaMode::Opaque);
    EXPECT_FALSE(material(0).hasAlphaTest());
    EXPECT_EQ(material(1).alphaMode, AlphaMode::Mask);
    EXPECT_EQ(material(1).alphaCutoff, 0.5f);  // the glTF default
    EXPECT_TRUE(material(1).hasAlphaTest());
    EXPECT_EQ(material(2).alphaCutoff, 0.25f);
    EXPECT_EQ(material(3).alphaMode, AlphaMode::Blend);
    EXPECT_TRUE(material(3).hasAlphaTest());
    // alpha >= 0 always meets a cutoff of 0: drawn exactly as opaque, no any-hit test.
    EXPECT_EQ(material(4).alphaMode, AlphaMode::Mask);
    EXPECT_FALSE(material(4).hasAlphaTest());
    // Above 1 hides everything; capped at 2 (still above any alpha) so it stays a finite float.
    EXPECT_EQ(material(5).alphaCutoff, 2.0f);
    EXPECT_EQ(material(6).alphaMode, AlphaMode::Opaque);  // the cutoff means nothing here
    EXPECT_FALSE(material(6).hasAlphaTest());
    EXPECT_TRUE(s.features() & graph::kSceneAlpha);
    EXPECT_FALSE(anyWarningContains(s, "alphaMode")) << "MASK and BLEND are supported now";
    EXPECT_EQ(graph::sceneFeatureNames(graph::kSceneAlpha), std::vector<std::string>{"alpha"});
}

TEST_F(SceneGltfAlpha, AlphaFeatureOnlyForUsedAlphaTestedMaterials) {
    // Only the first primitive (opaque) is drawn; the MASK material is unused.
    Scene unused = loadScene(
        write(quadGltf({R"({})", R"({"alphaMode": "MASK", "alphaCutoff": 0.5})"}, 1)).string());
    EXPECT_FALSE(unused.features() & graph::kSceneAlpha);
    // MASK with cutoff 0 is opaque: no any-hit test to compile in.
    Scene zero =
        loadScene(write(quadGltf({R"({"alphaMode": "MASK", "alphaCutoff": 0})"}, 1)).string());
    EXPECT_FALSE(zero.features() & graph::kSceneAlpha);
    Scene blend = loadScene(write(quadGltf({R"({"alphaMode": "BLEND"})"}, 1)).string());
    EXPECT_TRUE(blend.features() & graph::kSceneAlpha);
}

TEST_F(SceneGltfAlpha, BadCutoffNamesItsPointer) {
    for (const char* cutoff : {"-0.5", "-1e-30", "1e999", "-1e999", "\"half\""}) {
        // The bad value sits on material 1 so the pointer must name the right index.
        const std::string bad =
            std::string(R"({"alphaMode": "MASK", "alphaCutoff": )") + cutoff + "}";
        fs::path file = write(quadGltf({R"({"alphaMode": "MASK"})", bad}, 2));
        InputError e = loadError(file);
        EXPECT_EQ(e.pointer(), "/materials/1/alphaCutoff") << cutoff << ": " << e.what();
        EXPECT_EQ(e.file(), file.string());
    }
}

}  // namespace
