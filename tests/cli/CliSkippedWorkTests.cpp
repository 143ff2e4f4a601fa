// Work a scene or a graph does not need is skipped, and report.json shows it (issue 28 "skip
// what a scene doesn't need"): counters, not timings. Each test fails if the skipped work comes
// back: light samples in a scene without emitters, texture code in a scene without textures,
// ATrousNH tiles of a layer the mask leaves empty, tile lists rebuilt for an unchanged mask,
// cached passes that run again.
#include <gtest/gtest.h>

#include <string>

#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

const fs::path kSuzanne = kRepo / ".." / "shared" / "scenes" / "suzanne" / "suzanne.glb";
const fs::path kBoxTextured = kRepo / ".." / "shared" / "scenes" / "assimp-khronos-samples" /
                              "BoxTextured-glTF" / "BoxTextured.gltf";

// report.json of graphs/<graph> run for `frames` frames at 64x32 with `extra` arguments.
json runSkippedWork(const std::string& graph, std::vector<std::string> extra, int frames = 2) {
    TempDir tmp;
    std::vector<std::string> args = {"run",           (kRepo / "graphs" / graph).string(),
                                     "--out",         (tmp / "out").string(),
                                     "--size",        "64x32",
                                     "--frames",      std::to_string(frames),
                                     "--save-frames", "none",
                                     "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    const Result r = cli(args);
    EXPECT_EQ(r.code, 0) << r.describe();
    return r.code == 0 ? readReport(tmp / "out") : json::object();
}

uint64_t skippedWorkStat(const json& pass, const std::string& key) {
    return pass.at("statistics").at(key).get<uint64_t>();
}

}  // namespace

TEST(CliSkippedWork, SceneWithoutEmittersTracesNoLightSamples) {
    // Suzanne has no light and no emissive material: PathTrace compiles light sampling out and
    // traces no shadow ray; with run --sun (a punctual light) the same rays do cast them.
    const json dark = runSkippedWork("pathtrace.json",
                                     {"--scene", kSuzanne.string(), "--set", "pt.countRays=true"});
    ASSERT_TRUE(dark.contains("passes"));
    const json& pt = passNamed(dark, "pt");
    const std::string variant = pt.at("variant");
    EXPECT_NE(variant.find("no-emissive"), std::string::npos) << variant;
    EXPECT_NE(variant.find("no-punctual"), std::string::npos) << variant;
    EXPECT_GT(skippedWorkStat(pt, "rays_indirect"), 0u);  // primary hits: the GBuffer
    EXPECT_EQ(skippedWorkStat(pt, "rays_shadow_primary"), 0u);
    EXPECT_EQ(skippedWorkStat(pt, "rays_shadow_indirect"), 0u);

    const json lit = runSkippedWork(
        "pathtrace.json", {"--scene", kSuzanne.string(), "--sun", "--set", "pt.countRays=true"});
    ASSERT_TRUE(lit.contains("passes"));
    const json& litPt = passNamed(lit, "pt");
    EXPECT_NE(litPt.at("variant").get<std::string>().find(",punctual"), std::string::npos);
    EXPECT_GT(skippedWorkStat(litPt, "rays_shadow_primary"), 0u);
}

TEST(CliSkippedWork, SceneWithoutTexturesCompilesNoTextureFetch) {
    // SCENE_HAS_TEXTURES 0 compiles every texture fetch out of PathTrace and GBuffer; the
    // variant names the choice. A textured file turns it on.
    const json plain = runSkippedWork("pathtrace.json", {"--scene", "builtin:cornell"}, 1);
    ASSERT_TRUE(plain.contains("passes"));
    EXPECT_NE(passNamed(plain, "pt").at("variant").get<std::string>().find("no-textures"),
              std::string::npos);
    const json textured =
        runSkippedWork("pathtrace.json", {"--scene", kBoxTextured.string(), "--sun"}, 1);
    ASSERT_TRUE(textured.contains("passes"));
    const std::string variant = passNamed(textured, "pt").at("variant");
    EXPECT_NE(variant.find(",textures"), std::string::npos) << variant;
}

TEST(CliSkippedWork, EmptyFoveationLayersDispatchNoTiles) {
    // NH3LD (3/4/5 iterations, decreasing steps): level 0 updates the outer layer only and runs
    // full screen (it also seeds both state images), level 1 the middle and outer layers over
    // their tiles, levels 2-4 every layer. Radii beyond the image make the whole image fovea:
    // level 1 then has no tile to run on. Table 1's radii leave it most tiles but not all.
    const json covered = runSkippedWork(
        "peres_nh3ld.json", {"--mono", "--set", "mask.r0=1000", "--set", "mask.r1=2000"});
    ASSERT_TRUE(covered.contains("passes"));
    const json& dn = passNamed(covered, "dn");
    const uint64_t full = skippedWorkStat(dn, "tiles_full");
    EXPECT_EQ(full, 8u * 4u);  // 64x32 in 8x8 tiles
    const json& levels = dn.at("statistics").at("levels");
    ASSERT_EQ(levels.size(), 5u);
    EXPECT_EQ(levels[1].at("layers"), 6);  // middle | outer
    EXPECT_EQ(levels[1].at("tiles"), 0);
    EXPECT_EQ(skippedWorkStat(dn, "main_level_tiles"), 4 * full);
    EXPECT_EQ(skippedWorkStat(dn, "fill_levels_run"), 0u);  // every pixel traced: no hole to fill

    const json table1 = runSkippedWork("peres_nh3ld.json",
                                       {"--mono", "--set", "mask.r0=12", "--set", "mask.r1=16"});
    ASSERT_TRUE(table1.contains("passes"));
    const json& dn1 = passNamed(table1, "dn");
    const uint64_t level1 = dn1.at("statistics").at("levels")[1].at("tiles");
    EXPECT_GT(level1, 0u);
    EXPECT_LT(level1, full);
}

TEST(CliSkippedWork, UnchangedMaskBuildsTileListsOnceAndCachedPassesStayIdle) {
    // A still camera (the scene's): the mask and the G-buffer are made once, the tile lists are
    // built once, and the two cached passes dispatch nothing on later frames.
    const json report = runSkippedWork(
        "peres_nh3ld.json", {"--camera", "gltf:0", "--set", "mask.r0=6", "--set", "mask.r1=12"}, 3);
    ASSERT_TRUE(report.contains("passes"));
    EXPECT_EQ(skippedWorkStat(passNamed(report, "dn"), "tile_list_builds"), 1u);
    for (const std::string cached : {"gb", "mask"}) {
        const json& p = passNamed(report, cached);
        EXPECT_EQ(p.at("executions"), 1) << cached;
        EXPECT_EQ(p.at("status"), "cached") << cached;
    }
}
