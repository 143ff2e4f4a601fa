// glTF COLOR_0 (issue 16): the spec multiplies the base colour by the vertex colour
// (glTF 2.0 §3.7.2.1, §3.9.2); fovea ignored it. The loader reads float VEC3/VEC4 and normalized
// unsigned byte/short VEC4 into TriangleMesh::colors (white for primitives without), and the
// shared material fetch (sceneSurfaceMaterial, shaders/common/scene_sample.glsl) multiplies it in
// for GBuffer albedo and PathTrace shading. The scenes are built here: one quad seen by its own
// glTF camera and lit by a directional light; 16x16, one frame.
#include <cstring>

#include "core/scene/gltf/GltfLoader.h"
#include "core/util/Error.h"
#include "tests/cli/CliTestUtil.h"
#include "tests/unit/Base64.h"

using namespace fovea;
using namespace fovea::clitest;

namespace {

using test::base64;

template <class T>
std::vector<uint8_t> bytesOf(const std::vector<T>& values) {
    std::vector<uint8_t> out(values.size() * sizeof(T));
    std::memcpy(out.data(), values.data(), out.size());
    return out;
}

// The COLOR_0 accessor of the quad: its bytes (4 vertices), componentType, type, normalized.
struct Colors {
    std::vector<uint8_t> bytes;
    int componentType = 5126;
    std::string type = "VEC3";
    bool normalized = false;
};

// A quad [-1,1]^2 at z = 0 facing +Z, a camera at z = 2 looking down -Z that sees only the quad,
// a directional light shining along -Z. `colors` empty: no COLOR_0.
fs::path writeQuad(const fs::path& file, const std::string& baseColor,
                   const std::optional<Colors>& colors) {
    const std::vector<float> positions = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const std::vector<uint16_t> indices = {0, 1, 2, 0, 2, 3, 0, 0};  // padded to 4 bytes
    std::vector<uint8_t> geometry = bytesOf(positions);
    const std::vector<uint8_t> indexBytes = bytesOf(indices);
    geometry.insert(geometry.end(), indexBytes.begin(), indexBytes.end());
    std::string attributes = R"("POSITION": 0)";
    std::string accessors =
        R"({"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
            "min": [-1, -1, 0], "max": [1, 1, 0]},
           {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"})";
    std::string views = R"({"buffer": 0, "byteLength": 48},
                           {"buffer": 0, "byteOffset": 48, "byteLength": 12})";
    std::string buffers = R"({"byteLength": )" + std::to_string(geometry.size()) +
                          R"(, "uri": "data:application/octet-stream;base64,)" + base64(geometry) +
                          R"("})";
    if (colors) {
        attributes += R"(, "COLOR_0": 2)";
        accessors += R"(, {"bufferView": 2, "componentType": )" +
                     std::to_string(colors->componentType) + R"(, "count": 4, "type": ")" +
                     colors->type + R"(", "normalized": )" +
                     (colors->normalized ? "true" : "false") + "}";
        views += R"(, {"buffer": 1, "byteLength": )" + std::to_string(colors->bytes.size()) + "}";
        buffers += R"(, {"byteLength": )" + std::to_string(colors->bytes.size()) +
                   R"(, "uri": "data:application/octet-stream;base64,)" + base64(colors->bytes) +
                   R"("})";
    }
    writeText(file, R"({"asset": {"version": "2.0"}, "scene": 0,
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 3}]}},
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 2]},
                  {"extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.01}}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": )" +
                        baseColor + R"(, "metallicFactor": 0}}],
        "meshes": [{"primitives": [{"attributes": {)" +
                        attributes + R"(}, "indices": 1, "material": 0}]}],
        "accessors": [)" +
                        accessors + R"(], "bufferViews": [)" + views + R"(], "buffers": [)" +
                        buffers + "]}");
    return file;
}

Colors floatRgb(float r, float g, float b) {
    std::vector<float> v;
    for (int i = 0; i < 4; ++i) v.insert(v.end(), {r, g, b});
    return {bytesOf(v), 5126, "VEC3", false};
}

std::vector<float> channel(const std::vector<float>& rgba, int c) {
    std::vector<float> out;
    for (size_t i = size_t(c); i < rgba.size(); i += 4) out.push_back(rgba[i]);
    return out;
}

}  // namespace

TEST(SceneVertexColors, LoaderReadsEveryAllowedFormat) {
    TempDir tmp;
    auto load = [&](const std::optional<Colors>& c) {
        return scene::loadGltf(writeQuad(tmp / "q.gltf", "[1, 1, 1, 1]", c), {});
    };
    EXPECT_TRUE(load(std::nullopt).mesh.colors.empty()) << "no COLOR_0: no colour data";

    scene::Scene f = load(floatRgb(0.25f, 0.5f, 0.75f));
    ASSERT_EQ(f.mesh.colors.size(), f.mesh.positions.size());
    for (const glm::vec4& c : f.mesh.colors) EXPECT_EQ(c, glm::vec4(0.25f, 0.5f, 0.75f, 1.0f));

    std::vector<uint8_t> ubyte;
    for (int i = 0; i < 4; ++i) ubyte.insert(ubyte.end(), {255, 51, 0, 102});
    scene::Scene b = load(Colors{ubyte, 5121, "VEC4", true});
    ASSERT_EQ(b.mesh.colors.size(), b.mesh.positions.size());
    EXPECT_EQ(b.mesh.colors[0], glm::vec4(1.0f, 0.2f, 0.0f, 0.4f));

    std::vector<uint16_t> ushort;
    for (int i = 0; i < 4; ++i) ushort.insert(ushort.end(), {65535, 0, 13107, 65535});
    scene::Scene s = load(Colors{bytesOf(ushort), 5123, "VEC4", true});
    ASSERT_EQ(s.mesh.colors.size(), s.mesh.positions.size());
    EXPECT_EQ(s.mesh.colors[3], glm::vec4(1.0f, 0.0f, 0.2f, 1.0f));

    // Float colours outside [0, 1] (the spec's range) are an error naming the accessor.
    try {
        load(floatRgb(0.5f, 2.0f, 0.5f));
        ADD_FAILURE() << "loaded a COLOR_0 of 2";
    } catch (const InputError& e) {
        EXPECT_EQ(e.pointer(), "/accessors/2") << e.what();
        EXPECT_TRUE(contains(e.what(), "outside [0, 1]")) << e.what();
    }

    // Formats the spec does not allow for COLOR_0 are errors naming the attribute.
    for (const Colors& bad :
         {Colors{ubyte, 5121, "VEC4", false}, Colors{ubyte, 5121, "VEC2", true}}) {
        try {
            load(bad);
            ADD_FAILURE() << "loaded COLOR_0 " << bad.type << " normalized " << bad.normalized;
        } catch (const InputError& e) {
            EXPECT_EQ(e.pointer(), "/meshes/0/primitives/0/attributes/COLOR_0") << e.what();
        }
    }
}

// GBuffer albedo and PathTrace radiance of the quad: a COLOR_0 of 0.5 must give what a
// baseColorFactor of 0.5 gives (same seed: the same samples), and not what factor 1 gives.
TEST(SceneVertexColors, AlbedoAndPathTracingAreMultipliedByColor0) {
    TempDir tmp;
    const fs::path graph = tmp / "vc.json";
    writeText(graph, R"({"version": 1, "name": "vc", "passes": [{"name": "gb", "type": "GBuffer"},
        {"name": "pt", "type": "PathTrace", "params": {"spp": 1, "maxBounces": 1}}],
        "edges": [{"from": "gb.visibility", "to": "pt.visibility"},
                  {"from": "gb.albedo", "to": "pt.albedo"}],
        "outputs": ["gb.albedo", "pt.radiance"]})");
    auto render = [&](const std::string& name, const std::string& factor,
                      const std::optional<Colors>& colors) {
        const fs::path scene = writeQuad(tmp / (name + ".gltf"), factor, colors);
        Result r = cli({"run", graph.string(), "--scene", scene.string(), "--camera", "gltf:0",
                        "--size", "16x16", "--frames", "1", "--seed", "3", "--out",
                        (tmp / name).string(), "--quiet"});
        EXPECT_EQ(r.code, 0) << r.describe();
        return std::make_pair(pixels(tmp / name / "gb.albedo.exr"),
                              pixels(tmp / name / "pt.radiance.exr"));
    };
    const auto factor = render("factor", "[0.5, 0.25, 1, 1]", std::nullopt);
    const auto color = render("color", "[1, 1, 1, 1]", floatRgb(0.5f, 0.25f, 1.0f));
    const auto white = render("white", "[1, 1, 1, 1]", std::nullopt);
    ASSERT_EQ(factor.first.size(), 16u * 16u * 4u);
    ASSERT_EQ(color.first.size(), factor.first.size());
    for (size_t i = 0; i < factor.first.size(); ++i) {
        if (i % 4 == 3) continue;
        EXPECT_NEAR(color.first[i], factor.first[i], 1e-3) << "albedo value " << i;
        EXPECT_NEAR(color.second[i], factor.second[i], 1e-3 * std::max(1.0f, factor.second[i]))
            << "radiance value " << i;
    }
    // Albedo as expected, and the colour changed the picture (the test can fail).
    for (float g : channel(color.first, 1)) EXPECT_NEAR(g, 0.25f, 1e-3);
    for (float g : channel(white.first, 1)) EXPECT_NEAR(g, 1.0f, 1e-3);
    double lit = 0, litWhite = 0;
    for (float v : channel(color.second, 1)) lit += v;
    for (float v : channel(white.second, 1)) litWhite += v;
    EXPECT_GT(litWhite, 0.0) << "the quad is lit";
    EXPECT_NEAR(lit / litWhite, 0.25, 0.01) << "green radiance scales with COLOR_0's 0.25";
}
