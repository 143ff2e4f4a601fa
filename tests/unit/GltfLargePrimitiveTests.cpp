// Scenes at the size researchers bring (issue 28): one glTF primitive with more than 2^24
// indices loads (the old per-accessor limit refused 5.6M triangles), because an accessor with a
// buffer view is bounded by its bytes in the file; only accessors without one (zeros that cost
// memory but no bytes) keep the 2^24 limit, with an error naming the accessor and the reason.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/scene/BuiltinScenes.h"
#include "core/scene/gltf/GltfLoader.h"
#include "core/util/Error.h"

namespace fs = std::filesystem;
using namespace fovea;

namespace {

struct LargeFolder {
    LargeFolder() {
        path = fs::temp_directory_path() /
               ("fovea_large_" + std::to_string(::getpid()) + "_" +
                testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(path);
    }
    ~LargeFolder() {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
    fs::path path;
};

// The message of the InputError loading `file` throws ("" and a test failure if it loads).
std::string largeLoadError(const fs::path& file) {
    try {
        scene::loadGltf(file);
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << file << " loaded";
    return "";
}

// An n x n grid of quads in the plane y = 0 as one indexed primitive (2 n^2 triangles), with
// normals (so the loader keeps the shared vertices), bytes in grid.bin.
fs::path writeGrid(const fs::path& dir, uint32_t n) {
    const uint32_t side = n + 1;
    std::vector<float> positions, normals;
    positions.reserve(size_t(side) * side * 3);
    normals.reserve(size_t(side) * side * 3);
    for (uint32_t j = 0; j < side; ++j)
        for (uint32_t i = 0; i < side; ++i) {
            positions.insert(positions.end(), {float(i), 0.0f, float(j)});
            normals.insert(normals.end(), {0.0f, 1.0f, 0.0f});
        }
    std::vector<uint32_t> indices;
    indices.reserve(size_t(n) * n * 6);
    for (uint32_t j = 0; j < n; ++j)
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t a = j * side + i, b = a + 1, c = a + side, d = c + 1;
            indices.insert(indices.end(), {a, c, b, b, c, d});  // counter-clockwise from +y
        }
    const size_t pBytes = positions.size() * 4, nBytes = normals.size() * 4,
                 iBytes = indices.size() * 4;
    {
        std::ofstream bin(dir / "grid.bin", std::ios::binary);
        bin.write(reinterpret_cast<const char*>(positions.data()), std::streamsize(pBytes));
        bin.write(reinterpret_cast<const char*>(normals.data()), std::streamsize(nBytes));
        bin.write(reinterpret_cast<const char*>(indices.data()), std::streamsize(iBytes));
    }
    const auto s = [](size_t v) { return std::to_string(v); };
    std::ofstream(dir / "grid.gltf")
        << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
        "accessors": [
          {"bufferView": 0, "componentType": 5126, "count": )"
        << side * side << R"(, "type": "VEC3", "min": [0, 0, 0], "max": [)" << n << ", 0, " << n
        << R"(]},
          {"bufferView": 1, "componentType": 5126, "count": )"
        << side * side << R"(, "type": "VEC3"},
          {"bufferView": 2, "componentType": 5125, "count": )"
        << indices.size() << R"(, "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteLength": )"
        << s(pBytes) << R"(}, {"buffer": 0, "byteOffset": )" << s(pBytes) << R"(, "byteLength": )"
        << s(nBytes) << R"(}, {"buffer": 0, "byteOffset": )" << s(pBytes + nBytes)
        << R"(, "byteLength": )" << s(iBytes) << R"(}],
        "buffers": [{"byteLength": )"
        << s(pBytes + nBytes + iBytes) << R"(, "uri": "grid.bin"}]})";
    return dir / "grid.gltf";
}

TEST(SceneGltfLarge, PrimitiveWithMoreThan2To24IndicesLoads) {
    LargeFolder tmp;
    constexpr uint32_t n = 1700;  // 5,780,000 triangles, 17,340,000 indices > 16,777,216
    const scene::Scene s = scene::loadGltf(writeGrid(tmp.path, n));
    ASSERT_EQ(s.mesh.triangleCount(), size_t(2) * n * n);
    EXPECT_EQ(s.mesh.positions.size(), size_t(n + 1) * (n + 1));
    // The last triangle is the far corner's (b, c, d): every index made it through.
    const glm::uvec3 last = s.mesh.triangles.back();
    EXPECT_EQ(s.mesh.positions[last.z], glm::vec3(float(n), 0.0f, float(n)));
    EXPECT_EQ(s.bounds.max, glm::vec3(float(n), 0.0f, float(n)));
}

TEST(SceneGltfLarge, IndicesWithoutBufferViewKeepTheZeroAccessorLimit) {
    LargeFolder tmp;
    const fs::path file = tmp.path / "zeros.gltf";
    std::ofstream(file) << R"({"asset": {"version": "2.0"}, "scene": 0,
        "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
          {"componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0]},
          {"componentType": 5125, "count": 20000001, "type": "SCALAR"}]})";
    const std::string what = largeLoadError(file);
    EXPECT_NE(what.find("/accessors/1/count"), std::string::npos) << what;
    EXPECT_NE(what.find("16777216"), std::string::npos) << what;
    EXPECT_NE(what.find("without buffer view"), std::string::npos) << what;
}

// Issue 28's bad input: a primitive that claims 2^31 triangles (3 * 2^31 indices, past any
// 32-bit count) over a 12-byte buffer view is an input error at the accessor's count naming the
// bytes it would need, before anything is allocated for it: no crash, no hang, no wrapped count.
// (A view that really held 2^31 triangles, 25.8 GB, would meet the scene limit of 2^26 next.)
TEST(SceneGltfLarge, PrimitiveClaiming2To31TrianglesIsAnInputError) {
    LargeFolder tmp;
    const fs::path file = tmp.path / "claims.gltf";
    std::ofstream(tmp.path / "claims.bin", std::ios::binary) << std::string(48, '\0');
    std::ofstream(file) << R"({"asset": {"version": "2.0"}, "scene": 0,
        "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
          {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
           "min": [0, 0, 0], "max": [0, 0, 0]},
          {"bufferView": 1, "componentType": 5125, "count": 6442450944, "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36,
                         "byteLength": 12}],
        "buffers": [{"byteLength": 48, "uri": "claims.bin"}]})";
    const std::string what = largeLoadError(file);
    EXPECT_NE(what.find("/accessors/1/count"), std::string::npos) << what;
    EXPECT_NE(what.find("6442450944"), std::string::npos) << what;
    // The bytes it would need (4 per index) against the view's: checked in 64 bits.
    EXPECT_NE(what.find("25769803776 bytes"), std::string::npos) << what;
    EXPECT_NE(what.find("bufferView 1 has 12"), std::string::npos) << what;
}

// builtin:forest-10m holds every triangle in one mesh (no instancing): the count is pinned (a
// change here is a change of the benchmark), and it keeps builtin:forest's lights and camera.
TEST(SceneGltfLarge, Forest10mIsPinnedAndHoldsEveryTriangle) {
    const scene::Scene big = scene::loadBuiltinScene("builtin:forest-10m");
    const scene::Scene small = scene::loadBuiltinScene("builtin:forest");
    EXPECT_EQ(big.source, "builtin:forest-10m");
    EXPECT_EQ(big.mesh.triangleCount(), 11288656u);
    EXPECT_EQ(big.mesh.materialIds.size(), big.mesh.triangleCount());
    EXPECT_EQ(big.lights.size(), small.lights.size());
    EXPECT_EQ(big.materials.size(), small.materials.size());
    ASSERT_EQ(big.cameras.size(), 1u);
    EXPECT_EQ(big.cameras[0].position, small.cameras[0].position);
}

}  // namespace
