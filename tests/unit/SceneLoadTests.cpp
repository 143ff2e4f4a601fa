// Scene loading (core/scene/: GltfLoader, BuiltinScenes, SceneLoader, Scene). CPU only.
// Real scenes come from ../shared/scenes (skipped when absent); the malformed suites there
// (Khronos glTF-Validator cases with their expected reports, tinygltf and assimp broken files)
// must each load or throw InputError, and validator errors in data the scene uses must be
// rejected — see ValidatorErrorsInUsedDataAreRejected for the exact criterion. The synthetic
// files and the mutation test are in GltfSyntheticTests.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <set>

#include "core/graph/Pass.h"
#include "core/scene/BuiltinScenes.h"
#include "core/scene/gltf/GltfLoader.h"
#include "core/scene/SceneLoader.h"
#include "core/util/Error.h"
#include "tests/unit/SceneLoadTestUtil.h"

namespace fs = std::filesystem;
using namespace fovea;
using namespace fovea::scene;
using namespace fovea::scenetest;
using nlohmann::json;

namespace {

// ---------------------------------------------------------------------------------------------
// Real scenes

TEST(SceneLoadReal, CornellBoxBevy) {
    REQUIRE_SCENES();
    Scene s = load("cornell-box-bevy/CornellBox.glb");
    expectConsistent(s);
    EXPECT_EQ(s.mesh.triangleCount(), 36u);
    EXPECT_FLOAT_EQ(maxEmission(s), 100.0f);  // emissiveFactor 1 x emissive_strength 100
    EXPECT_EQ(emissiveTriangles(s), 2u);
    EXPECT_TRUE(s.cameras.empty());
    EXPECT_EQ(s.features(), uint32_t(graph::kSceneGeometry | graph::kSceneEmissive));
}

TEST(SceneLoadReal, CornellBoxOriginalAndNvidia) {
    REQUIRE_SCENES();
    Scene original = load("cornell-box-original/CornellBox-Original.gltf");
    expectConsistent(original);
    EXPECT_EQ(original.mesh.triangleCount(), 32u);
    EXPECT_FLOAT_EQ(maxEmission(original), 1.0f);

    Scene nvidia = load("cornell-box-nvidia/cornellBox.gltf");
    expectConsistent(nvidia);
    EXPECT_EQ(nvidia.mesh.triangleCount(), 16732u);
    EXPECT_FLOAT_EQ(maxEmission(nvidia), 10.0f);  // out of glTF range, kept as HDR
    // Its glass sphere is BLEND with alpha 0.05 (NV_materials_mdl glass, not read): nearly clear.
    EXPECT_TRUE(nvidia.features() & graph::kSceneAlpha);
    ASSERT_EQ(nvidia.cameras.size(), 1u);
    EXPECT_NEAR(nvidia.cameras[0].yfov, 0.7175f, 1e-3f);
    EXPECT_NEAR(nvidia.cameras[0].position.z, 19.99f, 0.02f);
    EXPECT_TRUE(anyWarningContains(nvidia, "/textures/0/source"));  // unused, image missing
    EXPECT_TRUE(anyWarningContains(nvidia, "NV_materials_mdl"));
}

TEST(SceneLoadReal, FlightHelmetTextures) {
    REQUIRE_SCENES();
    Scene s = load("flight-helmet/FlightHelmet.gltf");
    expectConsistent(s);
    EXPECT_EQ(s.mesh.triangleCount(), 94722u);
    // Base colour + occlusion-roughness-metal + normal per material; the lenses' normal map is
    // 32x32, every other texture 512x512. Every primitive is normal-mapped with a TANGENT.
    EXPECT_EQ(s.textures.size(), 15u);
    size_t small = 0;
    for (const Texture& t : s.textures) {
        small += t.width == 32u;
        EXPECT_TRUE(t.width == 512u || t.width == 32u) << t.width;
        EXPECT_EQ(t.height, t.width);
    }
    EXPECT_EQ(small, 1u);
    for (const Material& m : s.materials) EXPECT_GE(m.normalTexture, 0) << m.name;
    ASSERT_EQ(s.mesh.tangents.size(), s.mesh.positions.size());
    for (size_t i = 0; i < s.mesh.tangents.size(); i += 97) {
        EXPECT_NEAR(glm::length(glm::vec3(s.mesh.tangents[i])), 1.0f, 1e-4f) << i;
        EXPECT_NEAR(glm::dot(glm::vec3(s.mesh.tangents[i]), s.mesh.normals[i]), 0.0f, 1e-4f) << i;
    }
    // LensesMat is alphaMode BLEND (texture alpha 0.14-0.79): traced as stochastic transparency.
    EXPECT_EQ(s.features(),
              uint32_t(graph::kSceneGeometry | graph::kSceneTextures | graph::kSceneAlpha));
    const auto lenses = std::find_if(s.materials.begin(), s.materials.end(),
                                     [](const Material& m) { return m.name == "LensesMat"; });
    ASSERT_NE(lenses, s.materials.end());
    EXPECT_EQ(lenses->alphaMode, AlphaMode::Blend);
}

TEST(SceneLoadReal, PlainMeshesAndDracoVariants) {
    REQUIRE_SCENES();
    EXPECT_EQ(load("stanford-bunny/bunny.glb").mesh.triangleCount(), 5648u);
    EXPECT_EQ(load("suzanne/suzanne.glb").mesh.triangleCount(), 14842u);
    for (const char* draco : {"stanford-bunny/bunny-draco.glb", "suzanne/suzanne-draco.glb"}) {
        InputError e = loadError(scenesDir() / draco);
        EXPECT_EQ(e.pointer(), "/extensionsRequired/0") << e.what();
        EXPECT_NE(std::string(e.what()).find("KHR_draco_mesh_compression"), std::string::npos);
        EXPECT_NE(e.file().find(draco), std::string::npos);
    }
}

TEST(SceneLoadReal, SampleModels) {
    REQUIRE_SCENES();
    Scene cube = load("tinygltf-cube/Cube.gltf");
    EXPECT_EQ(cube.mesh.triangleCount(), 12u);
    EXPECT_EQ(cube.textures.size(), 2u);
    for (const char* box :
         {"BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Binary/BoxTextured.glb",
          "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
        Scene s = load(std::string("assimp-khronos-samples/") + box);
        expectConsistent(s);
        EXPECT_EQ(s.mesh.triangleCount(), 12u) << box;
        ASSERT_EQ(s.textures.size(), 1u) << box;
        EXPECT_EQ(s.features() & graph::kSceneTextures, uint32_t(graph::kSceneTextures));
    }
    Scene clearcoat = load("assimp-khronos-samples/ClearCoat-glTF/ClearCoatTest.gltf");
    EXPECT_EQ(clearcoat.mesh.triangleCount(), 37116u);
    EXPECT_TRUE(anyWarningContains(clearcoat, "KHR_materials_clearcoat"));
    Scene transform = load("assimp-khronos-samples/textureTransform/TextureTransformTest.gltf");
    EXPECT_EQ(transform.mesh.triangleCount(), 24u);
    // Supported (tests/unit/TextureViewTests.cpp checks what it does): no warning any more.
    EXPECT_FALSE(anyWarningContains(transform, "KHR_texture_transform"));
    Scene cameras = load("assimp-khronos-samples/cameras/Cameras.gltf");
    EXPECT_EQ(cameras.mesh.triangleCount(), 2u);
    ASSERT_EQ(cameras.cameras.size(), 1u);  // the orthographic one is skipped, with a warning
    EXPECT_NEAR(cameras.cameras[0].yfov, 0.7f, 1e-6f);
    EXPECT_TRUE(anyWarningContains(cameras, "orthographic"));
}

// ---------------------------------------------------------------------------------------------
// Malformed inputs

struct Outcome {
    bool loaded = false;
    std::string error;  // the InputError's what() when rejected
    std::string pointer;
    size_t warnings = 0;
    std::vector<std::string> used;
};

Outcome tryLoad(const fs::path& file, bool drawEveryMesh) {
    Outcome o;
    GltfLoadReport report;
    GltfLoadOptions options;
    options.drawEveryMesh = drawEveryMesh;
    try {
        Scene s = loadGltf(file, options, &report);
        expectConsistent(s);
        o.loaded = true;
        o.warnings = s.warnings.size();
    } catch (const InputError& e) {
        o.error = e.what();
        o.pointer = e.pointer();
    } catch (const std::exception& e) {
        ADD_FAILURE() << file << ": not an InputError: " << e.what();
    }
    o.used = report.usedPointers;
    if (std::getenv("FOVEA_SCENE_VERBOSE")) {
        std::cout << (o.loaded ? "LOADED   " : "REJECTED ") << file.string()
                  << (o.loaded ? "" : "\n    ") << o.error << "\n";
    }
    return o;
}

std::vector<fs::path> gltfFiles(const fs::path& dir) {
    std::vector<fs::path> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
        std::string ext = entry.path().extension().string();
        if (entry.is_regular_file() && (ext == ".gltf" || ext == ".glb"))
            files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

TEST(SceneLoadMalformed, EveryFileLoadsOrThrowsInputError) {
    REQUIRE_SCENES();
    auto start = std::chrono::steady_clock::now();
    // suite (+ " every mesh" in the drawEveryMesh mode) -> loaded, rejected, warnings
    std::map<std::string, std::array<size_t, 3>> tally;
    for (bool everyMesh : {false, true}) {
        for (const fs::path& file : gltfFiles(scenesDir() / "malformed")) {
            std::string suite = fs::relative(file, scenesDir() / "malformed").begin()->string();
            Outcome o = tryLoad(file, everyMesh);
            auto& t = tally[suite + (everyMesh ? " (drawEveryMesh)" : "")];
            (o.loaded ? t[0] : t[1]) += 1;
            t[2] += o.warnings;
            if (!o.loaded) {
                EXPECT_NE(o.error.find(file.filename().string()), std::string::npos) << o.error;
            }
        }
    }
    for (const auto& [suite, t] : tally) {
        std::cout << "[ malformed ] " << suite << ": " << t[0] << " loaded, " << t[1]
                  << " rejected, " << t[2] << " warnings\n";
    }
    EXPECT_EQ(tally["gltf-validator"][0] + tally["gltf-validator"][1], 263u);
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 60.0) << "a malformed file must not make the loader crawl";
}

struct ValidatorMessage {
    std::string code, pointer;
};

std::vector<ValidatorMessage> validatorErrors(const fs::path& gltf) {
    std::ifstream in(gltf.string() + ".report.json");
    json r = json::parse(in);
    std::vector<ValidatorMessage> out;
    for (const json& m : r["issues"]["messages"]) {
        if (m.value("severity", 1) != 0) continue;
        out.push_back(
            {m.value("code", ""), m.contains("pointer") ? m["pointer"].get<std::string>() : ""});
    }
    return out;
}

bool isPrefix(const std::string& a, const std::string& b) {  // a is b or an ancestor of b
    return a.empty() || b == a || b.rfind(a + "/", 0) == 0;
}

// Validator errors fovea never needs to reject, each for a stated reason.
bool harmless(const ValidatorMessage& m) {
    static const std::set<std::string> kCodes = {
        // min/max are optional metadata; fovea computes bounds from the data.
        "ACCESSOR_MIN_MISMATCH", "ACCESSOR_MAX_MISMATCH", "ACCESSOR_ELEMENT_OUT_OF_MIN_BOUND",
        "ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND", "MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS",
        // fovea renormalises normals and quaternions, and uses a node matrix as given.
        "ACCESSOR_VECTOR3_NON_UNIT", "ROTATION_NON_UNIT", "NODE_MATRIX_NON_TRS",
        // bookkeeping with no effect on reading: extension declarations, buffer view targets.
        "UNDECLARED_EXTENSION", "BUFFER_VIEW_TARGET_OVERRIDE",
        // skins and morph targets are not read (warned about when used).
        "MESH_PRIMITIVE_JOINTS_WEIGHTS_MISMATCH", "MESH_PRIMITIVES_UNEQUAL_TARGETS_COUNT",
        "NODE_SKIN_WITH_NON_SKINNED_MESH", "NODE_WEIGHTS_INVALID", "MESH_INVALID_WEIGHTS_COUNT",
        "NODE_SKIN_NO_SCENE",
        // attribute names: fovea looks up POSITION, NORMAL, TEXCOORD_0 and COLOR_0 only.
        "MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY",
        // a texture on a missing texture set: fovea itself rejects a textured material on a
        // primitive without TEXCOORD_0, and ignores (with a warning) textures on other sets.
        "MESH_PRIMITIVE_TOO_FEW_TEXCOORDS"};
    if (kCodes.count(m.code)) return true;
    // Parts of used entities fovea does not read.
    const std::string& p = m.pointer;
    for (const char* part : {"/targets", "/skin", "/weights", "/normalTexture", "/occlusionTexture",
                             "/extras", "/min", "/max", "/animations", "/skins"}) {
        if (p.find(part) != std::string::npos) return true;
    }
    size_t attributes = p.find("/attributes/");
    if (attributes != std::string::npos) {
        std::string semantic = p.substr(attributes + 12);
        return semantic != "POSITION" && semantic != "NORMAL" && semantic != "TEXCOORD_0" &&
               semantic != "COLOR_0";
    }
    return false;
}

// The criterion: a validator error is "in used data" when its pointer lies inside, or contains,
// an entity the loader reports as used (GltfLoadReport::usedPointers; an error without pointer,
// e.g. in the GLB container or the JSON syntax, concerns everything). Unless the error is
// harmless() — data fovea provably never reads — a file with such an error must be rejected.
// Errors only in unused entities may load (with warnings) or be rejected.
TEST(SceneLoadMalformed, ValidatorErrorsInUsedDataAreRejected) {
    REQUIRE_SCENES();
    size_t mustReject = 0, loadedWithErrors = 0, checked = 0;
    for (const fs::path& file : gltfFiles(scenesDir() / "malformed" / "gltf-validator")) {
        std::vector<ValidatorMessage> errors = validatorErrors(file);
        if (errors.empty()) continue;
        ++checked;
        Outcome o = tryLoad(file, true);
        if (!o.loaded) continue;
        ++loadedWithErrors;
        for (const ValidatorMessage& m : errors) {
            bool used = m.pointer.empty() ||
                        std::any_of(o.used.begin(), o.used.end(), [&](const std::string& u) {
                            return isPrefix(u, m.pointer) || isPrefix(m.pointer, u);
                        });
            if (used && !harmless(m)) {
                ++mustReject;
                ADD_FAILURE() << file << " loaded despite " << m.code << " at '" << m.pointer
                              << "', which the scene uses";
            }
        }
    }
    EXPECT_EQ(checked, 190u);  // cases whose report has errors
    EXPECT_EQ(mustReject, 0u);
    std::cout << "[ validator ] " << checked << " cases with errors: " << checked - loadedWithErrors
              << " rejected, " << loadedWithErrors << " loaded (errors only in unused data)\n";
}

// Valid and warning-only validator cases must not be rejected for anything but having nothing
// to draw or needing something fovea does not support.
TEST(SceneLoadMalformed, ValidatorCleanCasesAreNotRejectedWrongly) {
    REQUIRE_SCENES();
    for (const fs::path& file : gltfFiles(scenesDir() / "malformed" / "gltf-validator")) {
        if (!validatorErrors(file).empty()) continue;
        Outcome o = tryLoad(file, true);
        if (o.loaded) continue;
        bool acceptable = o.error.find("nothing to render") != std::string::npos ||
                          o.error.find("not supported") != std::string::npos ||
                          o.error.find("not available") != std::string::npos;
        EXPECT_TRUE(acceptable) << file << ": " << o.error;
    }
}

TEST(SceneLoadMalformed, KnownBrokenFilesNameTheProblem) {
    REQUIRE_SCENES();
    fs::path m = scenesDir() / "malformed";
    struct Case {
        const char* file;
        const char* pointer;
        const char* text;
    };
    for (const Case& c :
         {Case{"assimp/IndexOutOfRange/IndexOutOfRange.gltf", "/meshes/0/primitives/0/indices",
               "out of range"},
          Case{"assimp/RecursiveNodes/RecursiveNodes.gltf", "/nodes/", "cycle"},
          Case{"assimp/MissingBin/BoxTextured.gltf", "/buffers/0/uri", "file not found"},
          Case{"gltf-validator/mesh_data/index_buffer_oob.gltf", "/meshes/0/primitives/0/indices",
               "out of range"},
          Case{"gltf-validator/glb/invalid_magic.glb", "", "GLB"}}) {
        InputError e = loadError(m / c.file, true);  // validator files have no nodes
        EXPECT_EQ(e.pointer().rfind(c.pointer, 0), 0u) << c.file << ": " << e.what();
        EXPECT_NE(std::string(e.what()).find(c.text), std::string::npos) << e.what();
    }
}

// ---------------------------------------------------------------------------------------------
// Built-in scenes

TEST(SceneBuiltin, CornellBoxMatchesTheCornellData) {
    Scene s = loadBuiltinScene("builtin:cornell");
    expectConsistent(s);
    EXPECT_EQ(s.mesh.triangleCount(), 38u);  // 32 classic + the ceiling ring around the light
    EXPECT_EQ(emissiveTriangles(s), 2u);
    EXPECT_EQ(s.features(), uint32_t(graph::kSceneGeometry | graph::kSceneEmissive));
    EXPECT_NEAR(s.bounds.min.x, 0.0f, 1e-4f);
    EXPECT_NEAR(s.bounds.max.x, 556.0f, 1e-3f);
    EXPECT_NEAR(s.bounds.max.y, 548.8f, 1e-3f);
    EXPECT_NEAR(s.bounds.max.z, 559.2f, 1e-3f);
    ASSERT_EQ(s.cameras.size(), 1u);
    EXPECT_EQ(s.cameras[0].position, glm::vec3(278.0f, 273.0f, -800.0f));
    EXPECT_NEAR(s.cameras[0].yfov, 2.0 * std::atan(0.0125 / 0.035), 1e-6);
    // Walls face into the box, the light down, block faces away from their block.
    for (size_t t = 0; t < s.mesh.triangleCount(); ++t) {
        glm::uvec3 tri = s.mesh.triangles[t];
        glm::vec3 a = s.mesh.positions[tri.x], b = s.mesh.positions[tri.y],
                  c = s.mesh.positions[tri.z];
        glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        glm::vec3 centroid = (a + b + c) / 3.0f;
        const std::string& name = s.materials[s.mesh.materialIds[t]].name;
        auto all = [&](int axis, float v) { return a[axis] == v && b[axis] == v && c[axis] == v; };
        if (name == "light" || all(1, 548.8f)) {
            EXPECT_LT(n.y, -0.99f) << t;
        } else if (name == "green") {
            EXPECT_GT(n.x, 0.99f) << t;
        } else if (name == "red") {
            EXPECT_LT(n.x, -0.99f) << t;
        } else if (all(1, 0.0f)) {
            EXPECT_GT(n.y, 0.99f) << t;
        } else if (all(2, 559.2f)) {
            EXPECT_LT(n.z, -0.99f) << t;
        } else {
            glm::vec3 shortBlock(185.5f, 82.5f, 169.0f), tallBlock(368.5f, 165.0f, 351.25f);
            auto flat = [](glm::vec3 v) { return glm::vec2(v.x, v.z); };
            glm::vec3 block = glm::distance(flat(centroid), flat(shortBlock)) <
                                      glm::distance(flat(centroid), flat(tallBlock))
                                  ? shortBlock
                                  : tallBlock;
            EXPECT_GT(glm::dot(n, centroid - block), 0.0f) << t;
        }
    }
    EXPECT_EQ(s.mesh.normals[s.mesh.triangles[0].x],
              glm::normalize(glm::cross(s.mesh.positions[1] - s.mesh.positions[0],
                                        s.mesh.positions[2] - s.mesh.positions[0])));
}

TEST(SceneBuiltin, ScenesAreDeterministic) {
    for (const std::string& name : builtinSceneNames()) {
        // forest-10m is forest's generator at another layout (11.3M triangles: pinned, not
        // loaded twice, in SceneGltfLarge; this file also runs under the sanitizers).
        if (name == "builtin:forest-10m") continue;
        Scene a = loadScene(name), b = loadScene(name);
        EXPECT_EQ(a.mesh.positions, b.mesh.positions) << name;
        EXPECT_EQ(a.mesh.triangles, b.mesh.triangles) << name;
        EXPECT_EQ(a.mesh.materialIds, b.mesh.materialIds) << name;
        EXPECT_EQ(a.lights.size(), b.lights.size()) << name;
        expectConsistent(a);
    }
}

TEST(SceneBuiltin, ForestIsHeavyAndPinned) {
    Scene s = loadBuiltinScene("forest");
    // Pinned: the count depends only on the seeded decisions (clearings, tree kinds), so any
    // change here is a change of the benchmark.
    EXPECT_EQ(s.mesh.triangleCount(), 212416u);
    EXPECT_EQ(s.lights.size(), 80u);
    EXPECT_EQ(s.features(),
              uint32_t(graph::kSceneGeometry | graph::kSceneEmissive | graph::kScenePunctual));
    ASSERT_EQ(s.cameras.size(), 1u);
}

TEST(SceneBuiltin, AnalyticScenes) {
    Scene plane = loadBuiltinScene("builtin:plane");
    EXPECT_EQ(plane.mesh.triangleCount(), 4u);
    EXPECT_EQ(plane.features(), uint32_t(graph::kSceneGeometry | graph::kSceneEmissive));
    // The emitter covers almost the whole hemisphere: F -> 1, radiance -> albedo * Le.
    EXPECT_NEAR(builtin::planeCenterRadiance(), 0.5 * 0.99967, 1e-5);
    EXPECT_LT(builtin::planeCenterRadiance(), 0.5);

    Scene furnace = loadBuiltinScene("builtin:furnace");
    EXPECT_EQ(furnace.mesh.triangleCount(), 12u);
    EXPECT_EQ(emissiveTriangles(furnace), 12u);
    EXPECT_DOUBLE_EQ(builtin::furnaceRadiance(), 1.0);
    EXPECT_DOUBLE_EQ(builtin::furnaceRadiance(0), 0.5);
    EXPECT_DOUBLE_EQ(builtin::furnaceRadiance(1), 0.75);
    // Closed: every edge is shared by exactly two triangles.
    std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> edges;
    auto key = [](glm::vec3 p) { return std::array<float, 3>{p.x, p.y, p.z}; };
    for (const glm::uvec3& t : furnace.mesh.triangles) {
        for (int e = 0; e < 3; ++e) {
            auto a = key(furnace.mesh.positions[t[e]]),
                 b = key(furnace.mesh.positions[t[(e + 1) % 3]]);
            edges[{std::min(a, b), std::max(a, b)}]++;
        }
    }
    for (const auto& [edge, count] : edges) EXPECT_EQ(count, 2);
    // Normals point inwards.
    for (size_t i = 0; i < furnace.mesh.positions.size(); ++i) {
        EXPECT_LT(glm::dot(furnace.mesh.normals[i], furnace.mesh.positions[i]), 0.0f);
    }
}

TEST(SceneBuiltin, UnknownNameSuggestsAndLists) {
    try {
        loadScene("builtin:cornel");
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        std::string what = e.what();
        EXPECT_NE(what.find("did you mean 'cornell'"), std::string::npos) << what;
        EXPECT_NE(what.find("builtin:forest"), std::string::npos) << what;
        EXPECT_EQ(e.file(), "builtin:cornel");
    }
}

// ---------------------------------------------------------------------------------------------
// SceneLoader and Scene

TEST(SceneLoader, RejectsUnknownFilesByName) {
    for (const std::string& spec :
         {std::string("scene.obj"), std::string("/nonexistent/x.gltf"), std::string("")}) {
        try {
            loadScene(spec);
            ADD_FAILURE() << spec << " loaded";
        } catch (const InputError& e) {
            EXPECT_EQ(e.file(), spec);
        }
    }
}

TEST(SceneFeatures, BitsFollowUsedMaterials) {
    Scene s;
    EXPECT_EQ(s.features(), 0u);
    s.materials.resize(3);
    s.materials[1].baseColorTexture = 0;  // textured, but no triangle uses it
    s.materials[2].emissive = glm::vec3(1.0f);
    s.mesh.positions = {glm::vec3(0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)};
    s.mesh.normals.assign(3, glm::vec3(0, 0, 1));
    s.mesh.uvs.assign(3, glm::vec2(0));
    s.mesh.triangles = {glm::uvec3(0, 1, 2)};
    s.mesh.materialIds = {0};
    EXPECT_EQ(s.features(), uint32_t(graph::kSceneGeometry));
    s.mesh.materialIds = {2};
    EXPECT_EQ(s.features(), uint32_t(graph::kSceneGeometry | graph::kSceneEmissive));
    s.mesh.materialIds = {1};
    s.lights.emplace_back();
    EXPECT_EQ(s.features(),
              uint32_t(graph::kSceneGeometry | graph::kSceneTextures | graph::kScenePunctual));
    EXPECT_EQ(s.features() & graph::kSceneStereo, 0u);
}

TEST(SceneFeatures, DefaultCameraFramesTheBounds) {
    Scene s;
    s.bounds.grow(glm::vec3(0.0f));
    s.bounds.grow(glm::vec3(2.0f));
    CameraDesc c = s.defaultCamera();
    float radius = std::sqrt(3.0f);
    float distance = radius / std::sin(std::numbers::pi_v<float> / 8.0f);
    EXPECT_NEAR(c.yfov, std::numbers::pi_v<float> / 4.0f, 1e-6f);
    EXPECT_EQ(c.target, glm::vec3(1.0f));
    EXPECT_NEAR(c.position.x, 1.0f, 1e-6f);
    EXPECT_NEAR(c.position.y, 1.0f, 1e-6f);
    EXPECT_NEAR(c.position.z, 1.0f + distance, 1e-4f);
    EXPECT_EQ(c.up, glm::vec3(0.0f, 1.0f, 0.0f));
    EXPECT_GT(c.znear, 0.0f);
    EXPECT_LT(c.znear, distance - radius);
}

// `--camera frame` on a scene with its own camera looks the way that camera looks (the Cornell
// box is open towards its camera: framing it from +z saw the closed back wall, a black image).
TEST(SceneFeatures, DefaultCameraLooksLikeTheScenesCamera) {
    const Scene cornell = loadBuiltinScene("builtin:cornell");
    ASSERT_FALSE(cornell.cameras.empty());
    const CameraDesc c = cornell.defaultCamera();
    const glm::vec3 own = glm::normalize(cornell.cameras[0].target - cornell.cameras[0].position);
    const glm::vec3 framed = glm::normalize(c.target - c.position);
    EXPECT_GT(glm::dot(own, framed), 0.9999f);
    EXPECT_EQ(c.target, cornell.bounds.center());
    // The whole bounding sphere is in front of the camera.
    const float radius = 0.5f * glm::length(cornell.bounds.extent());
    EXPECT_GT(glm::length(c.target - c.position), radius);
    // A degenerate scene camera (target on the eye) falls back to the default direction.
    Scene s;
    s.bounds.grow(glm::vec3(0.0f));
    s.bounds.grow(glm::vec3(2.0f));
    CameraDesc broken;
    broken.position = broken.target = glm::vec3(1.0f);
    s.cameras.push_back(broken);
    EXPECT_GT(s.defaultCamera().position.z, 1.0f);
}

}  // namespace
