// End-to-end tests of the scene options of `fovea run`, `validate` and `reference`: --scene,
// --camera (path file or glTF camera), --stereo/--mono, --gaze, --sun, the scene block of
// report.json, culling without a scene, and input errors naming the flag or file. Tiny sizes:
// the suite runs on lavapipe.
#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

const fs::path kDolly = kRepo / "graphs" / "cameras" / "cornell_dolly.json";

}  // namespace

TEST(CliScene, RunReportsTheSceneAndTheVariants) {
    TempDir tmp;
    Result r = runSmall(kPathTraceGraph, tmp / "out", {"--scene", "builtin:cornell"});
    ASSERT_EQ(r.code, 0) << r.describe();
    json report = readReport(tmp / "out");
    const json& s = report.at("scene");
    EXPECT_EQ(s.at("spec"), "builtin:cornell");
    EXPECT_EQ(s.at("triangles"), 38);
    EXPECT_EQ(s.at("camera"), "gltf:0");  // Cornell's published camera
    EXPECT_EQ(s.at("stereo"), false);
    EXPECT_GT(s.at("bvh").at("nodes").get<int>(), 0);
    EXPECT_EQ(s.at("bvh").at("emissive_triangles"), 2);
    EXPECT_GT(s.at("gpu_bytes").get<int>(), 0);
    const json& pt = passNamed(report, "pt");
    EXPECT_EQ(pt.at("status"), "executed");
    const std::string variant = pt.at("variant");
    EXPECT_TRUE(contains(variant, "lambert") && contains(variant, "emissive") &&
                contains(variant, "no-textures"))
        << variant;
    // GBuffer is cached on the second frame: the camera did not move.
    EXPECT_EQ(passNamed(report, "gb").at("status"), "cached");
}

TEST(CliScene, StereoIsOneSideBySideImage) {
    TempDir tmp;
    Result r = cli({"run", kPathTraceGraph.string(), "--scene", "builtin:cornell", "--stereo",
                    "--size", "64x32", "--frames", "1", "--out", (tmp / "out").string()});
    ASSERT_EQ(r.code, 0) << r.describe();
    EXPECT_EQ(readReport(tmp / "out").at("scene").at("stereo"), true);
    auto image = ::fovea::image::readImage(tmp / "out" / "pt.radiance.exr");
    ASSERT_EQ(image.width, 64u);
    ASSERT_EQ(image.height, 32u);
    // Both eyes see the lit box: the mean radiance of each half is positive and similar.
    double half[2] = {0, 0};
    for (uint32_t y = 0; y < 32; ++y)
        for (uint32_t x = 0; x < 64; ++x) half[x / 32] += image.pixels[4 * (y * 64 + x)];
    EXPECT_GT(half[0], 0.0);
    EXPECT_GT(half[1], 0.0);
    EXPECT_LT(std::abs(half[0] - half[1]), 0.5 * std::max(half[0], half[1]));
}

TEST(CliScene, CameraPathMovesTheCameraAndCutsReset) {
    TempDir tmp;
    Result r = cli({"run", kPathTraceGraph.string(), "--scene", "builtin:cornell", "--camera",
                    kDolly.string(), "--size", "16x16", "--frames", "9", "--save-frames", "0,7,8",
                    "--out", (tmp / "out").string()});
    ASSERT_EQ(r.code, 0) << r.describe();
    json report = readReport(tmp / "out");
    EXPECT_EQ(report.at("scene").at("camera"), "path:" + kDolly.string());
    // The camera moves, so GBuffer ran every frame (never cached).
    EXPECT_EQ(passNamed(report, "gb").at("executions"), 9);
    auto f0 = pixels(tmp / "out" / "pt.radiance.frame0000.exr");
    auto f8 = pixels(tmp / "out" / "pt.radiance.frame0008.exr");
    EXPECT_NE(f0, f8);
}

TEST(CliScene, BadSceneOptionsNameTheFlag) {
    TempDir tmp;
    auto run = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = {
            "run", kPathTraceGraph.string(), "--out", (tmp / "o").string(), "--size", "8x8"};
        args.insert(args.end(), extra.begin(), extra.end());
        return cli(args);
    };
    expectInputError(run({"--scene", "builtin:cornel"}), {"cornell"});
    expectInputError(run({"--scene", (tmp / "missing.gltf").string()}),
                     {"--scene", "missing.gltf"});
    expectInputError(run({"--scene", "builtin:cornell", "--camera", "gltf:9"}), {"--camera"});
    expectInputError(run({"--scene", "builtin:cornell", "--camera", "gltf:nope"}),
                     {"--camera", "nope"});
    expectInputError(run({"--scene", "builtin:cornell", "--camera", (tmp / "nope.json").string()}),
                     {"nope.json"});
    expectInputError(run({"--scene", "builtin:cornell", "--gaze", "2,0.5"}), {"--gaze"});
    expectInputError(run({"--scene", "builtin:cornell", "--gaze", "0.5"}), {"--gaze"});
    expectInputError(run({"--scene", "builtin:cornell", "--stereo", "--mono"}), {"--stereo"});
    expectInputError(run({"--scene", "none", "--camera", kDolly.string()}), {"--camera"});
    // A camera path with a bad key names the file and the JSON pointer.
    writeText(tmp / "bad.json",
              R"({ "version": 1, "keyframes": [ { "frame": 0, "position": [0, 0, 1],
                   "target": [0, 0, 0], "yfov_deg": 500 } ] })");
    expectInputError(run({"--scene", "builtin:cornell", "--camera", (tmp / "bad.json").string()}),
                     {"bad.json", "/keyframes/0/yfov_deg"});
    EXPECT_FALSE(fs::exists(tmp / "o" / "report.json"));
}

TEST(CliScene, WithoutASceneScenePassesAreCulledWithAReason) {
    // Every output of graphs/pathtrace.json needs geometry: without a scene nothing is left to
    // run, which is an input error naming the reason.
    expectInputError(cli({"validate", kPathTraceGraph.string(), "--scene", "none"}),
                     {"pathtrace.json", "/outputs", "the scene lacks geometry"});
    Result ok = cli({"validate", kPathTraceGraph.string(), "--scene", "builtin:cornell"});
    ASSERT_EQ(ok.code, 0) << ok.describe();
    EXPECT_TRUE(contains(ok.out, "2 passes run, 0 culled")) << ok.describe();
}

TEST(CliScene, ReferenceRunsTheRequestedSamples) {
    TempDir tmp;
    Result r = cli({"reference", "--scene", "builtin:cornell", "--spp", "3", "--size", "16x16",
                    "--out", (tmp / "ref").string(), "--quiet"});
    ASSERT_EQ(r.code, 0) << r.describe();
    json report = readReport(tmp / "ref");
    EXPECT_EQ(report.at("frames"), 3);  // graphs/reference.json traces 1 spp per frame
    auto mean = pixels(tmp / "ref" / "acc.mean.frame0002.exr");
    double sum = 0;
    for (float v : mean) {
        ASSERT_TRUE(std::isfinite(v));
        sum += v;
    }
    EXPECT_GT(sum, 0.0);
    expectInputError(cli({"reference", "--spp", "0"}), {"--spp"});
}

TEST(CliScene, SceneWithoutLightsWarnsAndSunLightsIt) {
    // Suzanne has one grey material and no light.
    const fs::path file = kRepo / ".." / "shared" / "scenes" / "suzanne" / "suzanne.glb";
    if (!fs::exists(file)) GTEST_SKIP() << file << " not present";
    TempDir tmp;
    Result dark = runSmall(kPathTraceGraph, tmp / "dark", {"--scene", file.string()});
    ASSERT_EQ(dark.code, 0) << dark.describe();
    EXPECT_TRUE(contains(dark.err, "no light")) << dark.describe();
    Result sun = runSmall(kPathTraceGraph, tmp / "sun", {"--scene", file.string(), "--sun"});
    ASSERT_EQ(sun.code, 0) << sun.describe();
    EXPECT_FALSE(contains(sun.err, "no light")) << sun.describe();
    json report = readReport(tmp / "sun");
    const std::string variant = passNamed(report, "pt").at("variant");
    EXPECT_TRUE(contains(variant, "punctual") && !contains(variant, "no-punctual")) << variant;
    double sum = 0;
    for (float v : pixels(tmp / "sun" / "pt.radiance.frame0001.exr")) sum += v;
    EXPECT_GT(sum, 0.0);
}

TEST(CliScene, ReportCarriesPassStatistics) {
    // Pass::statistics reaches report.json: BMFR's sanitizer counters (docs/report-format.md).
    TempDir tmp;
    Result r =
        cli({"run", (kRepo / "graphs" / "koskela_bmfr.json").string(), "--size", "32x32",
             "--frames", "2", "--save-frames", "none", "--out", (tmp / "k").string(), "--quiet"});
    ASSERT_EQ(r.code, 0) << r.describe();
    json report = readReport(tmp / "k");
    bool found = false;
    for (const auto& p : report.at("passes")) {
        if (p.at("type") != "BMFR") {
            EXPECT_FALSE(p.contains("statistics")) << p.dump();
            continue;
        }
        found = true;
        const json& s = p.at("statistics");
        for (const char* key : {"nonfinite_color_samples", "nonfinite_geometry_pixels",
                                "negative_color_samples", "rank_deficient_blocks"})
            EXPECT_TRUE(s.contains(key) && s.at(key).is_number_unsigned()) << key;
        EXPECT_EQ(s.at("nonfinite_color_samples"), 0);  // PathTrace never emits NaN
    }
    EXPECT_TRUE(found);
}

TEST(CliScene, ReportCarriesPathTraceRayCounts) {
    // PathTrace with countRays: report.json has the counts; graphs/reference.json casts its own
    // primary rays, one per pixel and frame (16 x 16 x 2 frames).
    TempDir tmp;
    Result r = cli({"run", (kRepo / "graphs" / "reference.json").string(), "--size", "16x16",
                    "--frames", "2", "--save-frames", "none", "--set", "pt.countRays=true", "--out",
                    (tmp / "r").string(), "--quiet"});
    ASSERT_EQ(r.code, 0) << r.describe();
    json report = readReport(tmp / "r");
    for (const auto& p : report.at("passes")) {
        if (p.at("type") != "PathTrace") continue;
        const json& s = p.at("statistics");
        EXPECT_EQ(s.at("rays_primary"), 512);
        EXPECT_EQ(s.at("rays_total").get<uint64_t>(),
                  s.at("rays_primary").get<uint64_t>() +
                      s.at("rays_shadow_primary").get<uint64_t>() +
                      s.at("rays_indirect").get<uint64_t>() +
                      s.at("rays_shadow_indirect").get<uint64_t>() +
                      s.at("rays_last_brdf").get<uint64_t>());
        EXPECT_GT(s.at("rays_indirect").get<uint64_t>(), 0u);
    }
}
