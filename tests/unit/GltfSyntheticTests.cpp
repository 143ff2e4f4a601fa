// glTF loading on synthetic files written by the test: the supported subset feature by feature
// (interleaved attributes, normalized UVs, sparse accessors, mirrored and nested nodes, repaired
// and generated normals, 16-bit and grey PNGs, emissive strength, cameras, spot lights), errors
// naming file and JSON pointer, warnings for broken unused entities, and seeded mutations that
// must never end in anything but a scene or an InputError. CPU only.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <set>

#include "core/graph/Pass.h"
#include "core/scene/gltf/GltfLoader.h"
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

// ---------------------------------------------------------------------------------------------
// A synthetic file exercising the supported subset: interleaved attributes, normalized UVs, a
// sparse accessor without buffer view, a mirrored node, a hierarchy, a zero normal, generated flat
// normals, a LINES primitive, 16-bit and grey PNGs, emissive strength, a camera and a spot light.

using test::base64;

template <typename T>
void put(std::vector<uint8_t>& out, T value) {
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    out.insert(out.end(), p, p + sizeof(T));
}

std::vector<uint8_t> syntheticBuffer() {
    std::vector<uint8_t> b;
    const float quad[4][6] = {
        {0, 0, 0, 0, 0, 1}, {1, 0, 0, 0, 0, 1}, {1, 1, 0, 0, 0, 0}, {0, 1, 0, 0, 0, 1}};
    for (const auto& v : quad) {
        for (float f : v) put(b, f);  // 0: POSITION + NORMAL interleaved, stride 24
    }
    for (uint8_t uv : {0, 0, 0, 0, 255, 0, 0, 0, 255, 255, 0, 0, 0, 255, 0, 0}) put(b, uv);  // 96
    for (uint8_t i : {0, 1, 2, 0, 2, 3, 0, 0}) put(b, i);            // 112: indices (+2 padding)
    for (uint16_t i : {1, 2}) put(b, i);                             // 120: sparse indices
    for (float f : {1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.0f}) put(b, f);  // 124: sparse values
    return b;
}

json syntheticGltf(const std::string& bufferUri, size_t bufferBytes) {
    const char* png16 =
        "iVBORw0KGgoAAAANSUhEUgAAAAIAAAACEAYAAAAiJtFnAAAAGklEQVR4nGP4/58BCEAkDIO5//"
        "83MIAgAwMA+jANdX1opusAAAAASUVORK5CYII=";
    const char* pngGrey =
        "iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAAAAADRSSBWAAAAC0lEQVR4nGPgOgEAAN8A00shpUkAAAAASUVORK5CYI"
        "I=";
    json buffer = {{"byteLength", bufferBytes}};
    if (!bufferUri.empty()) buffer["uri"] = bufferUri;
    json gltf = json::parse(R"({
      "asset": {"version": "2.0"},
      "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_sheen"],
      "scene": 0,
      "scenes": [{"nodes": [0, 1, 2, 3, 4]}],
      "nodes": [
        {"mesh": 0, "translation": [10, 0, 0], "children": [5]},
        {"mesh": 1, "scale": [-1, 1, 1]},
        {"camera": 0, "translation": [0, 0, 5]},
        {"rotation": [0.7071068, 0, 0, 0.7071068], "translation": [0, 3, 0],
         "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"mesh": 2},
        {"mesh": 1, "translation": [0, 2, 0]}
      ],
      "meshes": [
        {"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]},
        {"primitives": [{"attributes": {"POSITION": 4}, "material": 1}]},
        {"primitives": [{"attributes": {"POSITION": 0}, "mode": 1}]}
      ],
      "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 0, "byteOffset": 12, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 1, "componentType": 5121, "normalized": true, "count": 4, "type": "VEC2"},
        {"bufferView": 2, "componentType": 5121, "count": 6, "type": "SCALAR"},
        {"componentType": 5126, "count": 3, "type": "VEC3",
         "sparse": {"count": 2, "indices": {"bufferView": 3, "componentType": 5123},
                    "values": {"bufferView": 4}}}
      ],
      "bufferViews": [
        {"buffer": 0, "byteOffset": 0, "byteLength": 96, "byteStride": 24},
        {"buffer": 0, "byteOffset": 96, "byteLength": 16, "byteStride": 4},
        {"buffer": 0, "byteOffset": 112, "byteLength": 6},
        {"buffer": 0, "byteOffset": 120, "byteLength": 4},
        {"buffer": 0, "byteOffset": 124, "byteLength": 24}
      ],
      "materials": [
        {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicRoughnessTexture": {"index": 1}},
         "emissiveFactor": [1, 0.5, 0], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}},
        {"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}, "doubleSided": true}
      ],
      "textures": [{"source": 0}, {"source": 1}, {"source": 7}],
      "cameras": [{"type": "perspective", "perspective": {"yfov": 0.6, "znear": 0.1}}],
      "extensions": {"KHR_lights_punctual": {"lights": [
        {"type": "spot", "color": [1, 0.5, 0.25], "intensity": 20,
         "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.5}}]}}
    })");
    gltf["buffers"] = json::array({buffer});
    gltf["images"] = json::array({{{"uri", std::string("data:image/png;base64,") + png16}},
                                  {{"uri", std::string("data:image/png;base64,") + pngGrey}}});
    return gltf;
}

// The synthetic scene as a GLB: JSON chunk, BIN chunk with the buffer (buffer 0 has no uri).
std::vector<uint8_t> syntheticGlb() {
    std::vector<uint8_t> bin = syntheticBuffer();
    std::string text = syntheticGltf("", bin.size()).dump();
    while (text.size() % 4) text += ' ';
    while (bin.size() % 4) bin.push_back(0);
    std::vector<uint8_t> glb;
    put(glb, 0x46546C67u);  // "glTF"
    put(glb, 2u);
    put(glb, uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    put(glb, uint32_t(text.size()));
    put(glb, 0x4E4F534Au);  // "JSON"
    glb.insert(glb.end(), text.begin(), text.end());
    put(glb, uint32_t(bin.size()));
    put(glb, 0x004E4942u);  // "BIN"
    glb.insert(glb.end(), bin.begin(), bin.end());
    return glb;
}

class SceneGltfSynthetic : public ::testing::Test {
protected:
    void SetUp() override {
        mDir = fs::temp_directory_path() / ("fovea-scene-test-" + std::to_string(::getpid()));
        fs::create_directories(mDir);
    }
    void TearDown() override { fs::remove_all(mDir); }
    fs::path write(const std::string& name, const std::string& text) {
        fs::path path = mDir / name;
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }
    fs::path writeGltf(const json& gltf) { return write("scene.gltf", gltf.dump()); }
    json embedded() {
        std::vector<uint8_t> buffer = syntheticBuffer();
        return syntheticGltf("data:application/octet-stream;base64," + base64(buffer),
                             buffer.size());
    }
    fs::path mDir;
};

void expectSyntheticScene(const Scene& s) {
    expectConsistent(s);
    ASSERT_EQ(s.mesh.triangleCount(), 4u);  // quad + the sparse triangle twice; LINES skipped
    EXPECT_EQ(s.mesh.positions[0], glm::vec3(10, 0, 0));
    EXPECT_EQ(s.mesh.uvs[2], glm::vec2(1, 1));
    EXPECT_EQ(s.mesh.normals[2], glm::vec3(0, 0, 1));  // the zero normal, repaired
    for (size_t t = 0; t < 4; ++t) {
        glm::uvec3 tri = s.mesh.triangles[t];
        glm::vec3 n = glm::cross(s.mesh.positions[tri.y] - s.mesh.positions[tri.x],
                                 s.mesh.positions[tri.z] - s.mesh.positions[tri.x]);
        EXPECT_GT(n.z, 0.0f) << "triangle " << t << " (mirrored nodes keep their front face)";
        EXPECT_EQ(s.mesh.normals[tri.x], glm::vec3(0, 0, 1));
    }
    // Depth-first: node 0's quad, its child node 5, then the mirrored node 1.
    auto corners = [&](size_t t) {
        std::set<std::array<float, 3>> out;
        for (int k = 0; k < 3; ++k) {
            glm::vec3 p = s.mesh.positions[s.mesh.triangles[t][k]];
            out.insert({p.x, p.y, p.z});
        }
        return out;
    };
    EXPECT_EQ(corners(2), (std::set<std::array<float, 3>>{{10, 2, 0}, {11, 2, 0}, {10, 3, 0}}));
    EXPECT_EQ(corners(3), (std::set<std::array<float, 3>>{{0, 0, 0}, {-1, 0, 0}, {0, 1, 0}}));

    ASSERT_EQ(s.textures.size(), 2u);
    EXPECT_EQ(s.textures[0].rgba8, (std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255,
                                                         255, 128, 128, 128, 0}));
    EXPECT_EQ(s.textures[1].rgba8, (std::vector<uint8_t>{10, 10, 10, 255, 200, 200, 200, 255}));
    const Material& quad = s.materials[s.mesh.materialIds[0]];
    EXPECT_EQ(quad.emissive, glm::vec3(4, 2, 0));
    EXPECT_EQ(quad.baseColorTexture, 0);
    EXPECT_EQ(quad.metallicRoughnessTexture, 1);
    EXPECT_TRUE(s.materials[s.mesh.materialIds[2]].doubleSided);

    ASSERT_EQ(s.cameras.size(), 1u);
    EXPECT_EQ(s.cameras[0].position, glm::vec3(0, 0, 5));
    EXPECT_EQ(s.cameras[0].target, glm::vec3(0, 0, 4));
    EXPECT_FLOAT_EQ(s.cameras[0].yfov, 0.6f);
    ASSERT_EQ(s.lights.size(), 1u);
    const Light& light = s.lights[0];
    EXPECT_EQ(light.type, Light::Type::Spot);
    EXPECT_EQ(light.position, glm::vec3(0, 3, 0));
    EXPECT_NEAR(light.direction.y, 1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(light.outerConeAngle, 0.5f);
    EXPECT_EQ(light.color, glm::vec3(1, 0.5f, 0.25f));
    for (const char* note : {"replaced", "LINES", "KHR_materials_sheen", "/textures/2/source"}) {
        EXPECT_TRUE(anyWarningContains(s, note)) << note;
    }
    EXPECT_EQ(s.features(), uint32_t(graph::kSceneGeometry | graph::kSceneEmissive |
                                     graph::kSceneTextures | graph::kScenePunctual));
}

TEST_F(SceneGltfSynthetic, EmbeddedBuffer) {
    expectSyntheticScene(loadScene(writeGltf(embedded()).string()));
}

TEST_F(SceneGltfSynthetic, ExternalBufferAndGlb) {
    std::vector<uint8_t> buffer = syntheticBuffer();
    write("data%20file.bin", std::string(buffer.begin(), buffer.end()));
    expectSyntheticScene(
        loadScene(writeGltf(syntheticGltf("data%2520file.bin", buffer.size())).string()));

    std::vector<uint8_t> glb = syntheticGlb();
    expectSyntheticScene(
        loadScene(write("scene.glb", std::string(glb.begin(), glb.end())).string()));
}

TEST_F(SceneGltfSynthetic, ErrorsNameFileAndPointer) {
    struct Case {
        std::function<void(json&)> edit;
        const char* pointer;
        const char* text;
    };
    const Case cases[] = {
        {[](json& g) { g["accessors"][0]["count"] = 1000; }, "/accessors/0/count",
         "bufferView 0 has 96"},
        {[](json& g) { g["accessors"][0]["count"] = 9007199254740993.0; }, "/accessors/0/count",
         ""},
        {[](json& g) { g["accessors"][3]["count"] = 7; }, "/accessors/3/count", ""},
        {[](json& g) { g["bufferViews"][2]["byteOffset"] = 144; }, "/bufferViews/2/byteLength",
         "exceeds buffer 0"},
        {[](json& g) { g["nodes"][5]["children"] = {0}; }, "/nodes/", "cycle"},
        {[](json& g) { g["nodes"][0]["mesh"] = "0"; }, "/nodes/0/mesh",
         "expected a non-negative integer"},
        {[](json& g) { g["meshes"][0]["primitives"][0]["material"] = 9; },
         "/meshes/0/primitives/0/material", "materials[9]"},
        {[](json& g) {
             g["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 2;
         },
         "/textures/2/source", "images[7]"},
        {[](json& g) { g["images"][0]["uri"] = "missing.png"; }, "/images/0", "file not found"},
        {[](json& g) { g["extensionsRequired"] = {"EXT_meshopt_compression"}; },
         "/extensionsRequired/0", "EXT_meshopt_compression"},
        {[](json& g) {
             g["nodes"][0]["translation"] = {1, 2};
         },
         "/nodes/0/translation", "expected 3 numbers"},
        {[](json& g) { g["scenes"][0]["nodes"] = {2}; }, "/scenes/0", "nothing to render"},
    };
    for (const Case& c : cases) {
        json gltf = embedded();
        c.edit(gltf);
        fs::path file = writeGltf(gltf);
        InputError e = loadError(file);
        EXPECT_EQ(e.pointer().rfind(c.pointer, 0), 0u) << e.what();
        EXPECT_NE(std::string(e.what()).find(c.text), std::string::npos) << e.what();
        EXPECT_EQ(e.file(), file.string());
    }
}

TEST_F(SceneGltfSynthetic, BrokenUnusedEntitiesAreWarnings) {
    json gltf = embedded();
    gltf["accessors"].push_back(
        {{"bufferView", 0}, {"componentType", 5126}, {"count", 999}, {"type", "VEC3"}});
    gltf["images"].push_back({{"uri", "data:image/png;base64,AAAA"}});
    gltf["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", 42}}}}}}});
    Scene s = loadScene(writeGltf(gltf).string());
    EXPECT_EQ(s.mesh.triangleCount(), 4u);
    for (const char* note :
         {"/accessors/5/count", "/images/2", "/meshes/3/primitives/0/attributes/POSITION"}) {
        EXPECT_TRUE(anyWarningContains(s, note)) << note;
    }
}

// Seeded mutations of the synthetic file: values replaced by hostile ones (huge, negative,
// fractional, wrong types), keys removed, bytes of the GLB and of the embedded data flipped.
// Every outcome must be a scene or an InputError.
TEST_F(SceneGltfSynthetic, MutationsNeverCrash) {
    std::mt19937_64 rng(20240613);
    const json base = embedded();
    const json flat = base.flatten();
    std::vector<std::string> leaves;
    for (const auto& [pointer, value] : flat.items()) leaves.push_back(pointer);
    const json hostile[] = {-1,
                            0,
                            1,
                            2,
                            3,
                            4,
                            5,
                            7,
                            255,
                            65535,
                            4294967295ull,
                            4294967296ull,
                            9007199254740992ull,
                            1e300,
                            -0.0,
                            0.5,
                            "x",
                            nullptr,
                            true,
                            json::array(),
                            json::object(),
                            {1, 2, 3}};
    // FOVEA_SCENE_MUTATIONS=<n> runs a longer campaign (n JSON and n/2 GLB mutations).
    const char* env = std::getenv("FOVEA_SCENE_MUTATIONS");
    const int rounds = env ? std::max(1, std::atoi(env)) : 300;
    size_t loaded = 0, rejected = 0;
    auto attempt = [&](const fs::path& file) {
        try {
            expectConsistent(loadScene(file.string()));
            ++loaded;
        } catch (const InputError&) {
            ++rejected;
        } catch (const std::exception& e) {
            ADD_FAILURE() << "not an InputError: " << e.what();
        }
    };
    for (int i = 0; i < rounds; ++i) {
        json gltf = base;
        for (int edits = 1 + int(rng() % 3); edits > 0; --edits) {
            json::json_pointer pointer(leaves[rng() % leaves.size()]);
            try {  // an earlier edit may have removed the path: then this edit is skipped
                json& parent = gltf.at(pointer.parent_pointer());
                if (rng() % 5 == 0) {
                    if (parent.is_object()) parent.erase(pointer.back());
                    if (parent.is_array()) parent.erase(std::stoul(pointer.back()));
                } else if (gltf.at(pointer).is_string() && rng() % 2) {
                    std::string& text = gltf.at(pointer).get_ref<std::string&>();
                    if (!text.empty()) text[rng() % text.size()] = "A/+=%0z"[rng() % 7];
                } else {
                    gltf.at(pointer) = hostile[rng() % std::size(hostile)];
                }
            } catch (const json::exception&) {
            }
        }
        attempt(writeGltf(gltf));
    }
    const std::vector<uint8_t> glb = syntheticGlb();
    const size_t binBytes = syntheticBuffer().size();
    for (int i = 0; i < rounds / 2; ++i) {
        std::vector<uint8_t> bytes = glb;
        for (int flips = 1 + int(rng() % 4); flips > 0; --flips) {
            size_t at = rng() % bytes.size();
            // Mostly the binary parts (header, chunk headers, BIN), where JSON parsing is no
            // shield.
            if (rng() % 2) at = rng() % 24 < 20 ? rng() % 20 : bytes.size() - 1 - rng() % binBytes;
            bytes[at] = uint8_t(rng());
        }
        if (rng() % 10 == 0) bytes.resize(rng() % bytes.size());
        attempt(write("mutated.glb", std::string(bytes.begin(), bytes.end())));
    }
    EXPECT_GT(loaded, 0u);
    EXPECT_GT(rejected, 0u);
    std::cout << "[ mutations ] " << loaded << " loaded, " << rejected << " rejected\n";
}

}  // namespace
