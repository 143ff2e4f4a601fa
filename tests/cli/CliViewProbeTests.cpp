// The view probe of `fovea run` (core/scene/ViewProbe.h, docs/scenes.md "Is the camera looking at
// the scene?"): report.json "primary_rays" and its warnings for a camera that sees no geometry
// and one inside a closed single-sided box, with --save-frames none (the black-output check needs
// saved images). Not in the sanitizer list (tests/CMakeLists.txt): four 16x16 GPU runs.
#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {}  // namespace

// --- primary-ray probe: report.json "primary_rays" and its warnings ------------------------------

// A camera that sees nothing: the probe says so on stderr and in report.json even when no output
// is saved (the black-output check needs saved images); the scene's own camera hits geometry.
TEST(CliViewProbe, PrimaryRaysThatHitNothingAreReported) {
    TempDir tmp;
    const fs::path camera = tmp / "away.json";
    writeText(camera, R"({"version": 1, "keyframes": [{"frame": 0, "position": [278, 273, -800],
        "target": [278, 273, -2000]}]})");
    Result away = cli({"run", kPathTraceGraph.string(), "--out", (tmp / "away").string(), "--size",
                       "16x16", "--frames", "1", "--save-frames", "none", "--scene",
                       "builtin:cornell", "--camera", camera.string()});
    ASSERT_EQ(away.code, 0) << away.describe();
    EXPECT_TRUE(contains(away.err, "primary rays hit geometry in 0.0%")) << away.describe();
    json report = json::parse(readText(tmp / "away" / "report.json"));
    EXPECT_EQ(report.at("primary_rays").at("hit_fraction"), 0.0);
    EXPECT_EQ(report["primary_rays"].at("probe_rays"), 1024);
    ASSERT_FALSE(report.at("warnings").empty());
    EXPECT_TRUE(contains(report["warnings"].back().get<std::string>(), "sees no geometry"));

    Result own =
        cli({"run", kPathTraceGraph.string(), "--out", (tmp / "own").string(), "--size", "16x16",
             "--frames", "1", "--save-frames", "none", "--scene", "builtin:cornell"});
    ASSERT_EQ(own.code, 0) << own.describe();
    EXPECT_FALSE(contains(own.err, "primary rays hit")) << own.describe();
    EXPECT_FALSE(contains(own.err, "inside geometry")) << own.describe();
    report = json::parse(readText(tmp / "own" / "report.json"));
    EXPECT_GT(report.at("primary_rays").at("hit_fraction").get<double>(), 0.5);
    EXPECT_LT(report["primary_rays"].at("inside_fraction").get<double>(), 0.1);
}

// A camera inside a closed single-sided box (faces outwards, as glTF winding defines the front):
// every probe ray meets a back face. Outside the same box, looking at it: no warning.
TEST(CliViewProbe, CameraInsideGeometryIsReported) {
    TempDir tmp;
    // Unit cube, 12 triangles wound counter-clockwise seen from outside; cameras at the centre
    // and at z = 5 (both look down -Z).
    const std::string positions =
        "-1,-1,-1, 1,-1,-1, 1,1,-1, -1,1,-1, -1,-1,1, 1,-1,1, 1,1,1, -1,1,1";
    std::vector<float> p;
    std::stringstream s(positions);
    for (std::string item; std::getline(s, item, ',');) p.push_back(std::stof(item));
    const std::vector<uint16_t> idx = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                       3, 7, 6, 3, 6, 2, 0, 4, 7, 0, 7, 3, 1, 2, 6, 1, 6, 5};
    std::string bytes(reinterpret_cast<const char*>(p.data()), p.size() * 4);
    bytes.append(reinterpret_cast<const char*>(idx.data()), idx.size() * 2);
    std::ofstream(tmp / "cube.bin", std::ios::binary) << bytes;
    writeText(tmp / "cube.gltf", R"({"asset": {"version": "2.0"}, "scene": 0,
        "scenes": [{"nodes": [0, 1, 2]}],
        "nodes": [{"mesh": 0}, {"camera": 0}, {"camera": 0, "translation": [0, 0, 5]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01}}],
        "materials": [{"emissiveFactor": [1, 1, 1]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                       "min": [-1, -1, -1], "max": [1, 1, 1]},
                      {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}],
        "bufferViews": [{"buffer": 0, "byteLength": 96}, {"buffer": 0, "byteOffset": 96,
                         "byteLength": 72}],
        "buffers": [{"byteLength": 168, "uri": "cube.bin"}]})");
    auto run = [&](const std::string& camera, const std::string& out) {
        return cli({"run", kPathTraceGraph.string(), "--out", (tmp / out).string(), "--size",
                    "16x16", "--frames", "1", "--save-frames", "none", "--scene",
                    (tmp / "cube.gltf").string(), "--camera", camera});
    };
    Result inside = run("gltf:0", "inside");
    ASSERT_EQ(inside.code, 0) << inside.describe();
    EXPECT_TRUE(contains(inside.err, "the camera looks inside geometry: 100%"))
        << inside.describe();
    json report = json::parse(readText(tmp / "inside" / "report.json"));
    EXPECT_EQ(report.at("primary_rays").at("inside_fraction"), 1.0);
    EXPECT_EQ(report["primary_rays"].at("hit_fraction"), 1.0);
    EXPECT_EQ(report["primary_rays"].at("back_face_hits"), 1024);

    Result outside = run("gltf:1", "outside");
    ASSERT_EQ(outside.code, 0) << outside.describe();
    EXPECT_FALSE(contains(outside.err, "inside geometry")) << outside.describe();
    report = json::parse(readText(tmp / "outside" / "report.json"));
    EXPECT_EQ(report.at("primary_rays").at("inside_fraction"), 0.0);
    EXPECT_GT(report["primary_rays"].at("hit_fraction").get<double>(), 0.2);
}
