// `--env` end to end (docs/scenes.md "Environment light"): `fovea run` with an environment EXR
// reports it (report.json scene.environment and features, PathTrace's variant) and shows it as
// the background; bad files and options exit 2 naming the file or option; the bench's `env` key
// is resolved against the bench file, enters the reference cache key, and bad values name their
// JSON pointer. Tiny sizes (lavapipe).
#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

// A 16x8 sky: radiance `value` in the upper half, 0.1 below (or NaN at texel (3, 2)).
fs::path writeSky(const fs::path& path, float value, bool withNaN = false) {
    fovea::image::ImageRGBA img;
    img.width = 16;
    img.height = 8;
    img.pixels.assign(16 * 8 * 4, 1.0f);
    for (uint32_t y = 0; y < 8; ++y)
        for (uint32_t x = 0; x < 16; ++x)
            for (int c = 0; c < 3; ++c) img.pixels[4 * (y * 16 + x) + c] = y < 4 ? value : 0.1f;
    if (withNaN) img.pixels[4 * (2 * 16 + 3) + 1] = std::nanf("");
    fovea::image::writeExr(path, img);
    return path;
}

}  // namespace

TEST(CliEnvironment, RunReportsTheEnvironmentAndShowsIt) {
    TempDir tmp;
    const fs::path sky = writeSky(tmp / "sky.exr", 2.0f);
    Result r = runSmall(kPathTraceGraph, tmp / "out",
                        {"--scene", "builtin:cornell", "--env", sky.string(), "--env-intensity",
                         "1.5", "--env-rotation", "30"});
    ASSERT_EQ(r.code, 0) << r.describe();
    const json report = readReport(tmp / "out");
    const json& s = report.at("scene");
    const json& env = s.at("environment");
    EXPECT_EQ(env.at("file"), sky.string());
    EXPECT_EQ(env.at("size"), json::array({16, 8}));
    EXPECT_EQ(env.at("intensity"), 1.5);
    EXPECT_EQ(env.at("rotation_degrees"), 30.0);
    const auto& features = s.at("features");
    EXPECT_NE(std::find(features.begin(), features.end(), "environment"), features.end());
    bool variant = false;
    for (const auto& p : report.at("passes"))
        if (p.at("name") == "pt") variant = contains(p.at("variant"), "environment");
    EXPECT_TRUE(variant);
}

TEST(CliEnvironment, BackgroundIsTheEnvironment) {
    TempDir tmp;
    const fs::path sky = writeSky(tmp / "sky.exr", 2.0f);
    // A camera path looking straight up from far above the Cornell box: no geometry in view.
    const fs::path path = tmp / "up.json";
    writeText(path, R"({ "version": 1, "keyframes": [ { "frame": 0, "position": [278, 5000, 278],)"
                    R"( "target": [278, 5001, 278], "up": [0, 0, 1] } ] })");
    Result r = cli({"run", kPathTraceGraph.string(), "--scene", "builtin:cornell", "--camera",
                    path.string(), "--env", sky.string(), "--env-intensity", "1.5", "--size", "8x8",
                    "--frames", "1", "--out", (tmp / "out").string()});
    ASSERT_EQ(r.code, 0) << r.describe();
    const auto image = fovea::image::readImage(tmp / "out" / "pt.radiance.exr");
    for (size_t i = 0; i < size_t(image.width) * image.height; ++i)
        EXPECT_FLOAT_EQ(image.pixels[4 * i], 3.0f) << "pixel " << i;  // 2 x intensity 1.5
}

TEST(CliEnvironment, BadFilesAndOptionsExit2NamingThem) {
    TempDir tmp;
    const fs::path sky = writeSky(tmp / "sky.exr", 1.0f);
    auto run = [&](std::vector<std::string> extra) {
        extra.insert(extra.begin(), {"--scene", "builtin:cornell"});
        return runSmall(kPathTraceGraph, tmp / "out", extra);
    };
    expectInputError(run({"--env", (tmp / "missing.exr").string()}), {"missing.exr", "not found"});
    expectInputError(run({"--env", writeSky(tmp / "nan.exr", 1.0f, true).string()}),
                     {"nan.exr", "texel (3, 2)"});
    writeText(tmp / "empty.hdr", "");
    expectInputError(run({"--env", (tmp / "empty.hdr").string()}), {"empty.hdr", "empty"});
    writeText(tmp / "junk.exr", "junk");
    expectInputError(run({"--env", (tmp / "junk.exr").string()}), {"junk.exr"});
    expectInputError(run({"--env-intensity", "2"}), {"--env-intensity", "without --env"});
    expectInputError(run({"--env", sky.string(), "--env-intensity", "-1"}), {"--env-intensity"});
    expectInputError(run({"--env", sky.string(), "--env-intensity", "nan"}), {"--env-intensity"});
    expectInputError(run({"--env", sky.string(), "--env-rotation", "inf"}), {"--env-rotation"});
    expectInputError(run({"--env", ""}), {"--env"});
    EXPECT_FALSE(fs::exists(tmp / "out" / "report.json"));
}

TEST(CliEnvironment, BenchEnvKey) {
    TempDir tmp;
    writeSky(tmp / "sky.exr", 1.0f);
    json spec = {{"version", 1},
                 {"scene", "builtin:cornell"},
                 {"env", {{"file", "sky.exr"}, {"intensity", 2}}},
                 {"size", {16, 16}},
                 {"frames", 2},
                 {"output", "pt.radiance"},
                 {"reference", {{"render", {{"spp", 4}}}}},
                 {"graphs", {{{"label", "pt"}, {"file", kPathTraceGraph.string()}}}}};
    auto bench = [&](const json& j, const std::string& out) {
        writeText(tmp / (out + ".bench.json"), j.dump(2));
        return cli({"bench", (tmp / (out + ".bench.json")).string(), "--out", (tmp / out).string(),
                    "--quiet"});
    };
    Result r = bench(spec, "out");
    ASSERT_EQ(r.code, 0) << r.describe();
    const json out = json::parse(readText(tmp / "out" / "bench.json"));
    EXPECT_EQ(out.at("env").at("file"), (tmp / "sky.exr").lexically_normal().string());
    EXPECT_EQ(out.at("env").at("intensity"), 2.0);
    const json key = json::parse(readText(tmp / "out" / "reference" / "key.json"));
    EXPECT_EQ(key.at("env").at("intensity"), 2.0);
    EXPECT_TRUE(key.at("env").contains("bytes"));

    // Bad values name the pointer.
    const std::vector<std::pair<json, std::vector<std::string>>> cases = {
        {json(3), {"/env", "file name"}},
        {json({{"file", "nope.exr"}}), {"/env/file", "nope.exr"}},
        {json({{"intensity", 2}}), {"/env", "missing field 'file'"}},
        {json({{"file", "sky.exr"}, {"intensity", -2}}), {"/env/intensity"}},
        {json({{"file", "sky.exr"}, {"rotation", "north"}}), {"/env/rotation"}},
        {json({{"file", "sky.exr"}, {"spin", 1}}), {"/env/spin", "unknown field"}},
    };
    int i = 0;
    for (const auto& [value, fragments] : cases) {
        json bad = spec;
        bad["env"] = value;
        Result e = bench(bad, "bad" + std::to_string(i++));
        EXPECT_EQ(e.code, 2) << e.describe();
        for (const auto& f : fragments) EXPECT_TRUE(contains(e.err, f)) << f << "\n" << e.err;
    }
}

// A real HDRI from Debian's blender-data (CC0, docs/scenes.md): loads, renders
// finite pixels, and adds light to the Cornell box (whose front is open).
TEST(CliEnvironment, RealHdriFromBlenderData) {
    const fs::path forest = "/usr/share/blender/datafiles/studiolights/world/forest.exr";
    ASSERT_TRUE(fs::exists(forest)) << "blender-data is installed by scripts/install-deps.sh";
    TempDir tmp;
    auto run = [&](const std::string& out, std::vector<std::string> extra) {
        std::vector<std::string> args = {"run",      kPathTraceGraph.string(),
                                         "--scene",  "builtin:cornell",
                                         "--size",   "32x32",
                                         "--frames", "1",
                                         "--out",    (tmp / out).string()};
        args.insert(args.end(), extra.begin(), extra.end());
        return cli(args);
    };
    Result r = run("out", {"--env", forest.string()});
    ASSERT_EQ(r.code, 0) << r.describe();
    const json report = readReport(tmp / "out");
    EXPECT_EQ(report.at("scene").at("environment").at("size"), json::array({1024, 512}));
    // forest.exr holds tiny negative texels (lossy compression): clamped, with a warning.
    const json& warnings = report.at("scene").at("warnings");
    ASSERT_EQ(warnings.size(), 1u) << warnings;
    EXPECT_TRUE(contains(warnings[0].get<std::string>(), "clamped to 0")) << warnings;
    const auto lit = fovea::image::readImage(tmp / "out" / "pt.radiance.exr");
    Result dark = run("dark", {});
    ASSERT_EQ(dark.code, 0) << dark.describe();
    const auto unlit = fovea::image::readImage(tmp / "dark" / "pt.radiance.exr");
    double sumLit = 0, sumUnlit = 0;
    for (size_t i = 0; i < lit.pixels.size(); i += 4) {
        EXPECT_TRUE(std::isfinite(lit.pixels[i])) << i;
        sumLit += lit.pixels[i + 1];
        sumUnlit += unlit.pixels[i + 1];
    }
    EXPECT_GT(sumLit, sumUnlit);  // the sky adds light (the box's front is open)
}
