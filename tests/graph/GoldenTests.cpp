// Golden-image tests (GoldenTest.*): shipped graphs rendered in-process at 32x32 for 3 frames and
// compared with tests/goldens/<name>/. Update them with FOVEA_UPDATE_GOLDENS=1 (docs/testing.md).
//
// GoldenHarness.* test the harness itself against goldens in a temporary directory: creating,
// matching, mismatch reports with actual and difference images, missing and stale goldens, the
// sidecar's tolerance, the environment switch.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "core/image/ImageIO.h"
#include "tests/graph/GoldenHarness.h"
#include "tests/graph/GpuTestFixture.h"

namespace fs = std::filesystem;
using fovea::test::GoldenMode;
using fovea::test::GoldenReport;
using fovea::test::GoldenSpec;
using fovea::test::GoldenStatus;
using nlohmann::json;

namespace {

class GoldenTest : public GpuTest {};

// A 32x32, 3-frame golden of `graph` (relative to the repository root) in tests/goldens/<name>/.
GoldenSpec golden(const std::string& name, const std::string& graph) {
    GoldenSpec spec;
    spec.name = name;
    spec.graph = graph;
    spec.width = 32;
    spec.height = 32;
    spec.frames = 3;
    return spec;
}

// A Cornell-box golden: 128x128 mono, or 128x64 side by side (two 64x64 eyes), one frame.
GoldenSpec cornellGolden(const std::string& name, const std::string& graph, bool stereo) {
    GoldenSpec spec = golden(name, graph);
    spec.scene = "builtin:cornell";
    spec.stereo = stereo;
    spec.width = 128;
    spec.height = stereo ? 64 : 128;
    spec.frames = 1;
    return spec;
}

// --- the goldens ------------------------------------------------------------------------------

// Seed 003 P3/P4's three preview methods (graphs/preview_*.json) on the Cornell box from inside,
// with the graphs' own equirect camera path (the gaze moves), 128x64, 3 frames of 2000 samples,
// the HMD view 48x48: equal budgets, different distributions, all bit-reproducible.
TEST_F(GoldenTest, Preview) {
    for (const std::string method : {"od", "vp", "fv"}) {
        GoldenSpec spec = golden("preview_" + method, "graphs/preview_" + method + ".json");
        spec.scene = "builtin:cornell";
        spec.cameraPath = "graphs/cameras/cornell_360.json";
        spec.width = 128;
        spec.height = 64;
        spec.params = {{"samples", {{"budget", 2000}}},
                       {"preview", {{"width", 48}, {"height", 48}}}};
        EXPECT_TRUE(fovea::test::goldenMatches(ctx(), spec)) << method;
    }
}

TEST_F(GoldenTest, Demo) {
    // Seeded noise accumulated over 3 frames (acc.mean) and an ACES-tonemapped gradient (tm.ldr).
    EXPECT_TRUE(
        fovea::test::goldenMatches(ctx(), golden("demo", "graphs/tests/utility_demo.json")));
}

TEST_F(GoldenTest, HistoryDifference) {
    // frame-index minus its delay-1 history: exactly 1 everywhere on the third frame.
    EXPECT_TRUE(fovea::test::goldenMatches(
        ctx(), golden("history_difference", "graphs/tests/history_difference.json")));
}

TEST_F(GoldenTest, CornellGBuffer) {
    // Ray-cast primary visibility of the Cornell box (seed 000 §3.1): surfaces, normals, albedo.
    EXPECT_TRUE(fovea::test::goldenMatches(
        ctx(), cornellGolden("cornell_gbuffer", "graphs/tests/golden_gbuffer.json", false)));
}

TEST_F(GoldenTest, CornellGBufferStereo) {
    // The same, side by side for two eyes in one dispatch (two 64x64 eye images).
    EXPECT_TRUE(fovea::test::goldenMatches(
        ctx(), cornellGolden("cornell_gbuffer_stereo", "graphs/tests/golden_gbuffer.json", true)));
}

TEST_F(GoldenTest, CornellPathTrace1spp) {
    // The P2 §3.1 1 spp configuration (graphs/pathtrace.json): bit-reproducible on one driver.
    EXPECT_TRUE(fovea::test::goldenMatches(
        ctx(), cornellGolden("cornell_pathtrace", "graphs/pathtrace.json", false)));
}

TEST_F(GoldenTest, CornellPathTraceStereo) {
    EXPECT_TRUE(fovea::test::goldenMatches(
        ctx(), cornellGolden("cornell_pathtrace_stereo", "graphs/pathtrace.json", true)));
}

// Seed 000's three pipelines (graphs/peres_*.json), stereo 128x64, two frames. Table 1's FHD
// radii 144/288 px per 960 px eye scale to 10/20 px for a 64 px eye.
GoldenSpec peresGolden(const std::string& variant) {
    GoldenSpec spec = cornellGolden("peres_" + variant, "graphs/peres_" + variant + ".json", true);
    spec.frames = 2;
    if (variant != "base") spec.params = {{"mask", {{"r0", 10}, {"r1", 20}}}};
    return spec;
}

TEST_F(GoldenTest, PeresBase) {
    EXPECT_TRUE(fovea::test::goldenMatches(ctx(), peresGolden("base")));
}

TEST_F(GoldenTest, PeresNH2LD) {
    EXPECT_TRUE(fovea::test::goldenMatches(ctx(), peresGolden("nh2ld")));
}

TEST_F(GoldenTest, PeresNH3LD) {
    EXPECT_TRUE(fovea::test::goldenMatches(ctx(), peresGolden("nh3ld")));
}

TEST_F(GoldenTest, PeresPipelinesFiniteWithoutHolesAndNotDarkened) {
    // Graph-level properties of the three pipelines: every pixel of the remodulated result is
    // finite and has a value (a = 1: the denoiser filled every unsampled pixel), and the
    // foveated pipelines are not darker than Base on average (an unsampled pixel counted as
    // black would darken the periphery by about the unsampled fraction, ~40%).
    double meanBase = 0;
    for (const std::string variant : {"base", "nh2ld", "nh3ld"}) {
        uint64_t seed = 0;
        auto outputs = fovea::test::renderGraphOutputs(ctx(), peresGolden(variant), seed);
        const auto it = std::find_if(outputs.begin(), outputs.end(),
                                     [](const auto& o) { return o.output == "rm.result"; });
        ASSERT_NE(it, outputs.end()) << variant;
        const auto& px = it->image.pixels;
        double sum = 0;
        for (size_t i = 0; i < px.size() / 4; ++i) {
            for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(px[i * 4 + c])) << variant;
            ASSERT_EQ(px[i * 4 + 3], 1.0f) << variant << ": hole at pixel " << i;
            sum += px[i * 4] + px[i * 4 + 1] + px[i * 4 + 2];
        }
        const double mean = sum / double(px.size() / 4);
        if (variant == "base")
            meanBase = mean;
        else
            EXPECT_NEAR(mean / meanBase, 1.0, 0.15) << variant << " vs Base mean brightness";
    }
}

TEST_F(GoldenTest, RemodulateInvertsPathTraceDemodulation) {
    // docs/passes/Remodulate.md: Remodulate(demodulated, albedo, emission) = radiance, with
    // PathTrace's albedo rule (near-black albedo neither divided nor multiplied). The emission
    // comes from GBuffer's rgba16f output, hence the relative tolerance.
    GoldenSpec spec = cornellGolden("unused", "graphs/tests/remodulate_roundtrip.json", false);
    spec.width = spec.height = 32;
    uint64_t seed = 0;
    auto outputs = fovea::test::renderGraphOutputs(ctx(), spec, seed);
    ASSERT_EQ(outputs.size(), 2u);
    const auto& radiance = outputs[0].image.pixels;
    const auto& result = outputs[1].image.pixels;
    size_t lit = 0;
    for (size_t i = 0; i < radiance.size(); ++i) {
        if (i % 4 == 3) {
            EXPECT_EQ(result[i], radiance[i]);  // alpha (sample count) kept
            continue;
        }
        ASSERT_NEAR(result[i], radiance[i], 1e-3 * std::max(1.0f, std::fabs(radiance[i])))
            << "value " << i;
        lit += radiance[i] > 0.05f;
    }
    EXPECT_GT(lit, radiance.size() / 8);  // a lit image, not a trivially equal black one
}

TEST_F(GoldenTest, KoskelaBMFR) {
    // Seed 003 P2's pipeline (graphs/koskela_bmfr.json): 1 spp, BMFR, TAA; four frames so that
    // both accumulations and the TAA history are exercised. 64x64 = 4 BMFR blocks (2x2 + offsets).
    GoldenSpec spec = cornellGolden("koskela_bmfr", "graphs/koskela_bmfr.json", false);
    spec.width = spec.height = 64;
    spec.frames = 4;
    EXPECT_TRUE(fovea::test::goldenMatches(ctx(), spec));
}

TEST_F(GoldenTest, ReBLUR) {
    // Seed 004's ReBLUR diffuse pipeline (graphs/reblur.json): 1 spp, RecurrentBlur temporal,
    // HistoryFix, RecurrentBlur spatial, Remodulate, TAA; four frames so that the recurrence
    // (rbs.history -> rbt.history), HistoryFix (N < 3) and the stabilization are exercised.
    GoldenSpec spec = cornellGolden("reblur", "graphs/reblur.json", false);
    spec.width = spec.height = 64;
    // At 64 rows the resolution scale (referenceHeight 1080) leaves HistoryFix nothing to rebuild;
    // as at 256 rows it rebuilds N = 0 from level 2 and N = 1 from level 1 (normal-aware).
    spec.params = {{"hf", {{"referenceHeight", 256}}}};
    spec.frames = 4;
    EXPECT_TRUE(fovea::test::goldenMatches(ctx(), spec));
}

// Issue 26: the diffuse/specular split on builtin:glossy (GGX), four still frames at 64x64.
GoldenSpec glossyGolden(const std::string& name, const std::string& graph) {
    GoldenSpec spec = golden(name, graph);
    spec.scene = "builtin:glossy";
    spec.width = spec.height = 64;
    spec.frames = 4;
    return spec;
}

TEST_F(GoldenTest, ReBLURDiffuseSpecular) {
    // graphs/reblur_diffuse_specular.json: PathTrace's split, one ReBLUR chain per signal (the
    // specular one with signal = specular, HistoryFix x roughness), two Remodulates, Combine.
    GoldenSpec spec =
        glossyGolden("reblur_diffuse_specular", "graphs/reblur_diffuse_specular.json");
    spec.params = {{"hfd", {{"referenceHeight", 256}}}, {"hfs", {{"referenceHeight", 256}}}};
    EXPECT_TRUE(fovea::test::goldenMatches(ctx(), spec));
}

TEST_F(GoldenTest, SVGFDiffuseSpecular) {
    // graphs/svgf_diffuse_specular.json: one SVGF per signal, each remodulating with its albedo.
    EXPECT_TRUE(fovea::test::goldenMatches(
        ctx(), glossyGolden("svgf_diffuse_specular", "graphs/svgf_diffuse_specular.json")));
}

TEST_F(GoldenTest, BMFRHistoryFix) {
    // graphs/bmfr_historyfix.json: HistoryFix after BMFR (count from bmfr.accumulated).
    GoldenSpec spec = cornellGolden("bmfr_historyfix", "graphs/bmfr_historyfix.json", false);
    spec.width = spec.height = 64;
    // As for ReBLUR: HistoryFix's levels as at 256 rows, so the demodulated, normal-aware rebuild
    // of frame 0 (every pixel N = 0) and of the dolly's disocclusions is in the golden.
    spec.params = {{"hf", {{"referenceHeight", 256}}}};
    spec.frames = 4;
    EXPECT_TRUE(fovea::test::goldenMatches(ctx(), spec));
}

TEST_F(GoldenTest, SVGF) {
    // Schied et al. 2017 in P2's configuration (graphs/svgf.json): 1 spp, SVGF, TAA; four frames
    // so that the moments, the temporal variance (h = 4) and the TAA history are exercised.
    GoldenSpec spec = cornellGolden("svgf", "graphs/svgf.json", false);
    spec.width = spec.height = 64;
    spec.frames = 4;
    EXPECT_TRUE(fovea::test::goldenMatches(ctx(), spec));
}

TEST_F(GoldenTest, KoskelaVisualPolarBMFR) {
    // Seed 003 P5's pipeline (graphs/koskela_vp_bmfr.json): Visual-Polar warp, GBuffer and 1 spp
    // PathTrace on the (rho, phi) grid (43x43 at 64x64), BMFR + TAA in VP, Unwarp with the
    // foveated blur; four frames of the Cornell dolly.
    GoldenSpec spec = cornellGolden("koskela_vp_bmfr", "graphs/koskela_vp_bmfr.json", false);
    spec.width = spec.height = 64;
    spec.frames = 4;
    EXPECT_TRUE(fovea::test::goldenMatches(ctx(), spec));
}

TEST_F(GoldenTest, KoskelaVisualPolarSVGF) {
    // P5's pipeline with SVGF in Visual-Polar space (graphs/koskela_vp_svgf.json): SVGF reprojects
    // with the GBuffer's Visual-Polar motion; four frames of the Cornell dolly.
    GoldenSpec spec = cornellGolden("koskela_vp_svgf", "graphs/koskela_vp_svgf.json", false);
    spec.width = spec.height = 64;
    spec.frames = 4;
    EXPECT_TRUE(fovea::test::goldenMatches(ctx(), spec));
}

TEST_F(GoldenTest, Chain20) {
    // 18 chained Combines of animated noise (aliased transients), tonemapped to rgba8.
    EXPECT_TRUE(fovea::test::goldenMatches(ctx(), golden("chain20", "graphs/tests/chain20.json")));
}

// --- the harness ------------------------------------------------------------------------------

std::string readText(const fs::path& path) {
    std::ifstream stream(path, std::ios::binary);
    std::stringstream buffer;
    buffer << stream.rdbuf();
    return buffer.str();
}

bool contains(const std::string& text, const std::string& fragment) {
    return text.find(fragment) != std::string::npos;
}

// Golden and failure roots in a fresh temporary directory, removed afterwards.
class GoldenHarness : public GpuTest {
protected:
    void SetUp() override {
        GpuTest::SetUp();
        static std::atomic<int> counter{0};
        std::random_device random;
        mRoot = fs::temp_directory_path() /
                ("fovea_golden_" +
                 std::string(testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                 std::to_string(::getpid()) + "_" + std::to_string(counter++) + "_" +
                 std::to_string(random() % 1000000));
        fs::remove_all(mRoot);
        fs::create_directories(mRoot);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(mRoot, ignored);
        GpuTest::TearDown();
    }

    // history_difference at 8x8, 2 frames: one rgba32f output, 1.0 everywhere.
    GoldenSpec spec(GoldenMode mode) const {
        GoldenSpec s;
        s.name = "hd";
        s.graph = "graphs/tests/history_difference.json";
        s.width = 8;
        s.height = 8;
        s.frames = 2;
        s.goldenRoot = mRoot / "goldens";
        s.failureRoot = mRoot / "failures";
        s.mode = mode;
        return s;
    }
    fs::path golden(const std::string& ext) const {
        return mRoot / "goldens" / "hd" / ("diff.result" + ext);
    }
    fs::path failure(const std::string& suffix) const {
        return mRoot / "failures" / "hd" / ("diff.result" + suffix);
    }

    GoldenReport run(const GoldenSpec& s) { return fovea::test::runGolden(ctx(), s); }

    // Creates the golden and checks it was written.
    void create() {
        GoldenReport r = run(spec(GoldenMode::Update));
        ASSERT_TRUE(r.ok()) << r.summary();
        ASSERT_EQ(r.outputs.size(), 1u);
        ASSERT_EQ(r.outputs[0].status, GoldenStatus::Written) << r.summary();
    }

    fs::path mRoot;
};

TEST_F(GoldenHarness, UpdateWritesGoldenAndSidecarThenCompareMatches) {
    create();
    ASSERT_TRUE(fs::is_regular_file(golden(".exr")));
    ASSERT_TRUE(fs::is_regular_file(golden(".json")));
    auto image = fovea::image::readImage(golden(".exr"));
    ASSERT_EQ(image.width, 8u);
    ASSERT_EQ(image.height, 8u);
    for (size_t p = 0; p < 64; ++p)
        for (int c = 0; c < 3; ++c) ASSERT_EQ(image.pixels[p * 4 + c], 1.0f) << p;

    json sidecar = json::parse(readText(golden(".json")));
    EXPECT_EQ(sidecar.at("graph"), "graphs/tests/history_difference.json");
    EXPECT_EQ(sidecar.at("output"), "diff.result");
    EXPECT_EQ(sidecar.at("format"), "rgba32f");
    EXPECT_EQ(sidecar.at("size"), json::array({8, 8}));
    EXPECT_EQ(sidecar.at("frames"), 2);
    EXPECT_EQ(sidecar.at("seed"), 0);
    EXPECT_EQ(sidecar.at("device"), ctx().deviceName());
    EXPECT_TRUE(sidecar.at("driver").is_string());
    EXPECT_EQ(sidecar.at("tolerance").at("rmse"), 1e-5);
    EXPECT_EQ(sidecar.at("tolerance").at("max_abs"), 1e-4);
    EXPECT_EQ(sidecar.at("created").get<std::string>().size(), 20u) << sidecar["created"];

    GoldenReport r = run(spec(GoldenMode::Compare));
    EXPECT_TRUE(r.ok()) << r.summary();
    ASSERT_EQ(r.outputs.size(), 1u);
    EXPECT_EQ(r.outputs[0].status, GoldenStatus::Match);
    EXPECT_EQ(r.outputs[0].compare.rmse, 0.0);
    EXPECT_FALSE(fs::exists(mRoot / "failures" / "hd")) << "nothing to report on a match";

    // Updating again with the same result leaves the files alone (clean diffs).
    const std::string before = readText(golden(".json"));
    r = run(spec(GoldenMode::Update));
    ASSERT_EQ(r.outputs.size(), 1u);
    EXPECT_EQ(r.outputs[0].status, GoldenStatus::Unchanged) << r.summary();
    EXPECT_EQ(readText(golden(".json")), before);
}

TEST_F(GoldenHarness, MissingGoldenFailsAndSaysHowToCreateIt) {
    GoldenReport r = run(spec(GoldenMode::Compare));
    EXPECT_FALSE(r.ok());
    ASSERT_EQ(r.outputs.size(), 1u);
    EXPECT_EQ(r.outputs[0].status, GoldenStatus::Missing);
    const std::string text = r.summary();
    EXPECT_TRUE(contains(text, golden(".exr").string())) << text;
    EXPECT_TRUE(contains(text, "FOVEA_UPDATE_GOLDENS=1")) << text;
    EXPECT_TRUE(contains(text, "--gtest_filter=GoldenHarness.MissingGolden")) << text;
    EXPECT_TRUE(fs::is_regular_file(failure(".actual.exr"))) << "actual written for review";
    EXPECT_FALSE(fs::exists(golden(".exr"))) << "compare mode never writes goldens";

    // goldenMatches turns it into a failed assertion carrying the same text.
    auto result = fovea::test::goldenMatches(ctx(), spec(GoldenMode::Compare));
    EXPECT_FALSE(result);
    EXPECT_TRUE(contains(result.message(), "FOVEA_UPDATE_GOLDENS=1")) << result.message();
}

TEST_F(GoldenHarness, MismatchWritesActualAndDifference) {
    create();
    // Corrupt one pixel of the golden by 0.5 in green.
    auto image = fovea::image::readImage(golden(".exr"));
    const size_t pixel = 3 * 8 + 5;
    image.pixels[pixel * 4 + 1] -= 0.5f;
    fovea::image::writeExr(golden(".exr"), image);

    GoldenReport r = run(spec(GoldenMode::Compare));
    EXPECT_FALSE(r.ok());
    ASSERT_EQ(r.outputs.size(), 1u);
    const auto& o = r.outputs[0];
    EXPECT_EQ(o.status, GoldenStatus::Mismatch);
    EXPECT_DOUBLE_EQ(o.compare.maxAbs, 0.5);
    EXPECT_NEAR(o.compare.rmse, std::sqrt(0.25 / (64 * 3)), 1e-9);
    EXPECT_EQ(o.actual, failure(".actual.exr"));
    EXPECT_EQ(o.difference, failure(".diff.exr"));
    for (const char* suffix : {".actual.exr", ".actual.png", ".diff.exr", ".diff.png"})
        EXPECT_TRUE(fs::is_regular_file(failure(suffix))) << suffix;
    auto diff = fovea::image::readImage(failure(".diff.exr"));
    ASSERT_EQ(diff.pixels.size(), 64u * 4u);
    for (size_t p = 0; p < 64; ++p)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(diff.pixels[p * 4 + c], p == pixel && c == 1 ? 0.5f : 0.0f) << p << c;
    auto actual = fovea::image::readImage(failure(".actual.exr"));
    EXPECT_EQ(actual.pixels[pixel * 4 + 1], 1.0f);

    const std::string text = r.summary();
    for (const std::string& fragment :
         {std::string("MISMATCH"), std::string("rmse"), std::string("max_abs 0.5"),
          failure(".actual.exr").string(), failure(".diff.exr").string(), golden(".exr").string(),
          std::string("FOVEA_UPDATE_GOLDENS=1")})
        EXPECT_TRUE(contains(text, fragment)) << fragment << "\n" << text;

    // Updating accepts the new result; the next comparison matches and clears the failure files.
    ASSERT_TRUE(run(spec(GoldenMode::Update)).ok());
    r = run(spec(GoldenMode::Compare));
    EXPECT_TRUE(r.ok()) << r.summary();
    EXPECT_FALSE(fs::exists(failure(".diff.exr")));
}

TEST_F(GoldenHarness, ToleranceComesFromTheSidecar) {
    create();
    auto image = fovea::image::readImage(golden(".exr"));
    image.pixels[0] += 1e-3f;  // over the default float max_abs (1e-4)
    fovea::image::writeExr(golden(".exr"), image);
    EXPECT_FALSE(run(spec(GoldenMode::Compare)).ok());

    json sidecar = json::parse(readText(golden(".json")));
    sidecar["tolerance"] = {{"rmse", 1e-3}, {"max_abs", 2e-3}};
    std::ofstream(golden(".json")) << sidecar.dump(2);
    GoldenReport r = run(spec(GoldenMode::Compare));
    EXPECT_TRUE(r.ok()) << r.summary();

    // A hand-loosened tolerance survives an update; an explicit one in the spec replaces it.
    ASSERT_TRUE(run(spec(GoldenMode::Update)).ok());
    EXPECT_EQ(json::parse(readText(golden(".json")))["tolerance"]["max_abs"], 2e-3);
    GoldenSpec strict = spec(GoldenMode::Update);
    strict.tolerance = fovea::test::GoldenTolerance{.rmse = 0, .maxAbs = 0};
    ASSERT_TRUE(run(strict).ok());
    EXPECT_EQ(json::parse(readText(golden(".json")))["tolerance"]["max_abs"], 0.0);
    EXPECT_TRUE(run(spec(GoldenMode::Compare)).ok()) << "identical result passes tolerance 0";

    // A sidecar without a usable tolerance is reported, not ignored.
    sidecar.erase("tolerance");
    std::ofstream(golden(".json")) << sidecar.dump(2);
    r = run(spec(GoldenMode::Compare));
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.outputs[0].status, GoldenStatus::Invalid) << r.summary();
}

TEST_F(GoldenHarness, GoldenForAnotherRunIsStale) {
    create();
    GoldenSpec bigger = spec(GoldenMode::Compare);
    bigger.width = 16;
    GoldenReport r = run(bigger);
    EXPECT_FALSE(r.ok());
    ASSERT_EQ(r.outputs.size(), 1u);
    EXPECT_EQ(r.outputs[0].status, GoldenStatus::Stale);
    EXPECT_TRUE(contains(r.summary(), "size [8,8] (test runs [16,8])")) << r.summary();

    GoldenSpec reseeded = spec(GoldenMode::Compare);
    reseeded.seed = 5;
    r = run(reseeded);
    EXPECT_FALSE(r.ok());
    EXPECT_TRUE(contains(r.summary(), "seed 0 (test runs 5)")) << r.summary();
}

TEST_F(GoldenHarness, GoldenOfNoOutputIsStale) {
    create();
    fs::copy_file(golden(".exr"), mRoot / "goldens" / "hd" / "old.output.exr");
    fs::copy_file(golden(".json"), mRoot / "goldens" / "hd" / "old.output.json");
    GoldenReport r = run(spec(GoldenMode::Compare));
    EXPECT_FALSE(r.ok());
    ASSERT_EQ(r.outputs.size(), 2u);
    EXPECT_EQ(r.outputs[0].status, GoldenStatus::Match);
    EXPECT_EQ(r.outputs[1].status, GoldenStatus::Stale);
    EXPECT_TRUE(contains(r.summary(), "old.output.exr")) << r.summary();

    // Update removes it.
    EXPECT_TRUE(run(spec(GoldenMode::Update)).ok());
    EXPECT_FALSE(fs::exists(mRoot / "goldens" / "hd" / "old.output.exr"));
    EXPECT_FALSE(fs::exists(mRoot / "goldens" / "hd" / "old.output.json"));
    EXPECT_TRUE(run(spec(GoldenMode::Compare)).ok());
}

TEST_F(GoldenHarness, EnvironmentSelectsTheMode) {
    const char* old = std::getenv("FOVEA_UPDATE_GOLDENS");
    const std::optional<std::string> saved = old ? std::optional<std::string>(old) : std::nullopt;

    ::setenv("FOVEA_UPDATE_GOLDENS", "1", 1);
    EXPECT_EQ(fovea::test::modeFromEnvironment(), GoldenMode::Update);
    GoldenReport r = run(spec(GoldenMode::FromEnvironment));
    EXPECT_EQ(r.mode, GoldenMode::Update);
    EXPECT_TRUE(r.ok()) << r.summary();
    EXPECT_TRUE(fs::is_regular_file(golden(".exr")));

    ::setenv("FOVEA_UPDATE_GOLDENS", "0", 1);
    EXPECT_EQ(fovea::test::modeFromEnvironment(), GoldenMode::Compare);
    ::unsetenv("FOVEA_UPDATE_GOLDENS");
    r = run(spec(GoldenMode::FromEnvironment));
    EXPECT_EQ(r.mode, GoldenMode::Compare);
    EXPECT_TRUE(r.ok()) << r.summary();

    if (saved) ::setenv("FOVEA_UPDATE_GOLDENS", saved->c_str(), 1);
}

TEST(GoldenTolerance, DefaultsByFormat) {
    using fovea::test::defaultTolerance;
    for (const char* format : {"rgba8", "r8"}) {  // one 8-bit code, not two
        EXPECT_GT(defaultTolerance(format).maxAbs, 1.0 / 255.0) << format;
        EXPECT_LT(defaultTolerance(format).maxAbs, 2.0 / 255.0) << format;
    }
    EXPECT_EQ(defaultTolerance("rgba16f").maxAbs, 2e-3);
    EXPECT_EQ(defaultTolerance("rgba32f").maxAbs, 1e-4);
    EXPECT_EQ(defaultTolerance("rgba32ui").maxAbs, 1e-4);
    EXPECT_EQ(defaultTolerance("R8G8Snorm").maxAbs, 1e-4);  // unnamed: treated as float
}

}  // namespace
