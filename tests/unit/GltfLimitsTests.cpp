// glTF values that overflow 32-bit floats (issue 16, finding 6): a vertex at 3e38 or an
// emissiveFactor of 1e39 rendered all black with exit 0; they are InputErrors naming the pointer
// now. CPU only.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/scene/gltf/GltfLoader.h"
#include "core/util/Error.h"
#include "tests/unit/Base64.h"

namespace fs = std::filesystem;
using namespace fovea;

namespace {

using test::base64;

std::string number(double v) {
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", v);
    return text;
}

// One emissive triangle; `far` is the x coordinate of its third vertex. `bufferUri` empty: the
// positions in a data URI; else that URI, and the bytes are written to `bufferFile`.
fs::path writeTriangle(const fs::path& dir, float far, const std::string& emissive,
                       const std::string& bufferUri = "", const fs::path& bufferFile = {}) {
    const float positions[9] = {0, 0, 0, 1, 0, 0, far, 1, 0};
    std::vector<uint8_t> bytes(sizeof positions);
    std::memcpy(bytes.data(), positions, sizeof positions);
    const std::string text =
        R"({"asset": {"version": "2.0"}, "scene": 0,
        "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
        "materials": [{"emissiveFactor": )" +
        emissive + R"(}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [)" +
        number(std::max(1.0f, far)) + R"(, 1, 0]}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "buffers": [{"byteLength": 36,
                     "uri": ")" +
        (bufferUri.empty() ? "data:application/octet-stream;base64," + base64(bytes) : bufferUri) +
        R"("}]})";
    if (!bufferUri.empty()) {
        std::ofstream(bufferFile, std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    }
    const fs::path file = dir / "triangle.gltf";
    std::ofstream(file) << text;
    return file;
}

InputError gltfError(const fs::path& file, const scene::GltfLoadOptions& options = {}) {
    try {
        scene::loadGltf(file, options);
    } catch (const InputError& e) {
        return e;
    }
    ADD_FAILURE() << file << " loaded";
    return InputError("", "", "");
}

struct LimitsFolder {
    LimitsFolder() {
        path = fs::temp_directory_path() /
               ("fovea_limits_" + std::to_string(::getpid()) + "_" +
                testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(path);
    }
    ~LimitsFolder() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
    fs::path path;
};

}  // namespace

TEST(SceneGltfLimits, OrdinaryTriangleLoads) {
    LimitsFolder tmp;
    EXPECT_NO_THROW(scene::loadGltf(writeTriangle(tmp.path, 1.0f, "[1, 1, 1]"), {}));
}

TEST(SceneGltfLimits, VertexAt3e38IsAnError) {
    LimitsFolder tmp;
    const float far = 3e38f;
    InputError e = gltfError(writeTriangle(tmp.path, far, "[1, 1, 1]"));
    EXPECT_EQ(e.pointer(), "/accessors/0") << e.what();
    EXPECT_NE(std::string(e.what()).find("vertex 2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1e15"), std::string::npos) << e.what();
}

TEST(SceneGltfLimits, EmissiveFactor1e39IsAnError) {
    LimitsFolder tmp;
    InputError e = gltfError(writeTriangle(tmp.path, 1.0f, "[1e39, 1, 1]"));
    EXPECT_EQ(e.pointer(), "/materials/0/emissiveFactor") << e.what();
    // Large HDR emission below the cap still loads (warned as above 1).
    EXPECT_NO_THROW(scene::loadGltf(writeTriangle(tmp.path, 1.0f, "[1e6, 1, 1]"), {}));
}

// A buffer URI that leaves the scene's folder used to be opened (and its size echoed): refused now
// unless the caller allows external URIs; in-folder files and subfolders still load.
TEST(SceneGltfLimits, UrisLeavingTheSceneFolderAreRefused) {
    LimitsFolder tmp;
    const fs::path sceneDir = tmp.path / "scene";
    fs::create_directories(sceneDir / "data");
    const fs::path outside = tmp.path / "secret.bin";
    for (const std::string& uri :
         {std::string("../secret.bin"), outside.string(), std::string("data/../../secret.bin")}) {
        const fs::path file = writeTriangle(sceneDir, 1.0f, "[1, 1, 1]", uri, outside);
        InputError e = gltfError(file);
        EXPECT_EQ(e.pointer(), "/buffers/0/uri") << uri << ": " << e.what();
        EXPECT_NE(std::string(e.what()).find("outside the scene's folder"), std::string::npos)
            << e.what();
        EXPECT_EQ(std::string(e.what()).find("bytes"), std::string::npos)
            << "the file's size is echoed: " << e.what();
        // The message names the glTF file and the URI as written.
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("'" + uri + "'"), std::string::npos) << e.what();
        // Allowed on request, absolute paths included (tinygltf used to join an absolute URI to
        // the scene folder as text and fail).
        scene::GltfLoadOptions allow;
        allow.allowExternalUris = true;
        EXPECT_NO_THROW(scene::loadGltf(file, allow)) << uri;
    }
    EXPECT_NO_THROW(scene::loadGltf(
        writeTriangle(sceneDir, 1.0f, "[1, 1, 1]", "data/tri.bin", sceneDir / "data" / "tri.bin"),
        {}));  // '+' is a literal '+' in a URI path (tinygltf's own decoder reads it as a space).
    EXPECT_NO_THROW(scene::loadGltf(writeTriangle(sceneDir, 1.0f, "[1, 1, 1]", "data/a+b%20c.bin",
                                                  sceneDir / "data" / "a+b c.bin"),
                                    {}));
}
