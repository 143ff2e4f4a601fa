// `fovea run --reference R [--reference-output OUT]`: per-frame and mean error figures in
// report.json (docs/report-format.md "reference"), a single reference for every frame or a
// directory of per-frame references, the default compared output, and input errors (size
// mismatch, missing file or frame, NaN, unknown output) naming the file or option. Tiny sizes.
#include "eval/flip/Flip.h"
#include "eval/metrics/ImageMetrics.h"
#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;
using fovea::image::ImageRGBA;

namespace {

Result runWithReference(const fs::path& out, const std::string& frames,
                        std::vector<std::string> extra) {
    std::vector<std::string> args = {"run",   kDemoGraph.string(), "--out", out.string(), "--size",
                                     "32x32", "--frames",          frames};
    args.insert(args.end(), extra.begin(), extra.end());
    return cli(args);
}

json reportOf(const fs::path& out) {
    return json::parse(readText(out / "report.json"));
}

void expectMetricKeys(const json& m) {
    for (const char* key : {"mse", "rmse", "rmse_percent", "rel_mse", "psnr_db", "ssim"})
        EXPECT_TRUE(m.contains(key)) << key << " missing in " << m;
}

}  // namespace

TEST(CliReference, TheRunItselfAsReferenceHasZeroError) {
    TempDir tmp;
    Result first = runWithReference(tmp / "a", "3", {"--save-frames", "all"});
    ASSERT_EQ(first.code, 0) << first.describe();
    // Per-frame directory: the same seed renders bit-identical frames.
    Result again = runWithReference(
        tmp / "b", "3", {"--reference", (tmp / "a").string(), "--reference-output", "acc.mean"});
    ASSERT_EQ(again.code, 0) << again.describe();
    const json ref = reportOf(tmp / "b").at("reference");
    EXPECT_EQ(ref.at("mode"), "per-frame");
    EXPECT_EQ(ref.at("output"), "acc.mean");
    ASSERT_EQ(ref.at("frames").size(), 3u);
    for (const auto& f : ref["frames"]) {
        expectMetricKeys(f);
        EXPECT_EQ(f.at("rmse").get<double>(), 0.0) << f;
        EXPECT_TRUE(f.at("psnr_db").is_null()) << "infinite PSNR is null: " << f;
        EXPECT_NEAR(f.at("ssim").get<double>(), 1.0, 1e-12);
        EXPECT_TRUE(contains(f.at("reference"), "acc.mean.frame000")) << f;
    }
    EXPECT_TRUE(ref["frames"][0].at("temporal_error").is_null());
    EXPECT_TRUE(ref["frames"][1].at("temporal_error").is_number());
    EXPECT_EQ(ref.at("mean").at("rmse").get<double>(), 0.0);
    EXPECT_TRUE(ref["mean"].at("psnr_db").is_null());

    // One file for every frame: only the frame it was taken from matches exactly.
    Result single =
        runWithReference(tmp / "c", "3",
                         {"--reference", (tmp / "a" / "acc.mean.frame0002.exr").string(),
                          "--reference-output", "acc.mean"});
    ASSERT_EQ(single.code, 0) << single.describe();
    const json s = reportOf(tmp / "c").at("reference");
    EXPECT_EQ(s.at("mode"), "single");
    EXPECT_GT(s["frames"][0].at("rmse").get<double>(), 0.0);
    EXPECT_EQ(s["frames"][2].at("rmse").get<double>(), 0.0);
    EXPECT_GT(s.at("mean").at("rmse").get<double>(), 0.0);
    EXPECT_TRUE(s["mean"].at("psnr_db").is_null()) << "one identical frame: mean PSNR infinite";
    // Error per eccentricity band (0-5, 5-20, 20+ degrees): every pixel in one band; zero for the
    // identical frame, non-zero in some band of a different frame.
    uint64_t pixels[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
        const json& bands = (k == 0 ? ref : s).at("mean").at("bands");
        ASSERT_EQ(bands.size(), 3u);
        for (const auto& b : bands) pixels[k] += b.at("pixels").get<uint64_t>();
    }
    EXPECT_GT(pixels[0], 0u);
    EXPECT_EQ(pixels[0], pixels[1]);
    for (const auto& b : ref["frames"][1].at("bands")) EXPECT_EQ(b.at("rmse").get<double>(), 0.0);
    double band0 = 0;
    for (const auto& b : s["frames"][0].at("bands")) band0 += b.at("rmse").get<double>();
    EXPECT_GT(band0, 0.0);
}

TEST(CliReference, KnownOffsetGivesKnownErrorsAndTemporalError) {
    TempDir tmp;
    Result first = runWithReference(tmp / "a", "2", {"--save-frames", "all"});
    ASSERT_EQ(first.code, 0) << first.describe();
    // Default compared output: the first float output listed (pt.radiance; tm.ldr is 8-bit).
    const ImageRGBA f0 = fovea::image::readImage(tmp / "a" / "pt.radiance.frame0000.exr");
    const ImageRGBA f1 = fovea::image::readImage(tmp / "a" / "pt.radiance.frame0001.exr");
    const float offset = 0.25f;
    ImageRGBA shifted = f0;
    for (size_t i = 0; i < shifted.pixels.size(); ++i)
        if (i % 4 != 3) shifted.pixels[i] += offset;
    fovea::image::writeExr(tmp / "shifted.exr", shifted);
    Result r = runWithReference(tmp / "b", "2", {"--reference", (tmp / "shifted.exr").string()});
    ASSERT_EQ(r.code, 0) << r.describe();
    const json ref = reportOf(tmp / "b").at("reference");
    EXPECT_EQ(ref.at("output"), "pt.radiance");
    EXPECT_NEAR(ref["frames"][0].at("rmse").get<double>(), offset, 1e-5);
    EXPECT_NEAR(ref["frames"][0].at("rmse_percent").get<double>(), 100.0 * offset, 1e-3);
    EXPECT_NEAR(ref["frames"][0].at("psnr_db").get<double>(), 20.0 * std::log10(1.0 / offset),
                1e-3);
    const auto expected = fovea::eval::computeMetrics(f1, shifted);
    EXPECT_NEAR(ref["frames"][1].at("rmse").get<double>(), expected.rmse, 1e-9);
    EXPECT_NEAR(ref["frames"][1].at("ssim").get<double>(), expected.ssim, 1e-9);
    EXPECT_NEAR(ref.at("mean").at("rmse").get<double>(), 0.5 * (offset + expected.rmse), 1e-5);
    // Temporal error: mean |ΔY| between the two compared frames (Schied et al. 2017).
    const double temporal = fovea::eval::temporalError(f0, f1);
    EXPECT_GT(temporal, 0.0) << "1 spp frames differ";
    EXPECT_NEAR(ref.at("temporal_error").get<double>(), temporal, 1e-9);
    EXPECT_NEAR(ref["frames"][1].at("temporal_error").get<double>(), temporal, 1e-9);
}

// ꟻLIP of each frame: the library's figure on the saved frame and the reference, HDR for the
// float output and LDR for Tonemap's 8-bit one; the options need --reference.
TEST(CliReference, FlipPerFrameMatchesTheLibrary) {
    TempDir tmp;
    Result first = runWithReference(tmp / "a", "2", {"--save-frames", "all", "--seed", "5"});
    ASSERT_EQ(first.code, 0) << first.describe();
    const fs::path reference = tmp / "a" / "pt.radiance.frame0001.exr";
    Result r = runWithReference(tmp / "b", "2",
                                {"--save-frames", "all", "--reference", reference.string()});
    ASSERT_EQ(r.code, 0) << r.describe();
    const json ref = reportOf(tmp / "b").at("reference");
    EXPECT_EQ(ref.at("flip").at("mode"), "hdr");
    const auto expected =
        fovea::eval::computeFlip(fovea::image::readImage(tmp / "b" / "pt.radiance.frame0000.exr"),
                                 fovea::image::readImage(reference), fovea::eval::FlipOptions{});
    EXPECT_NEAR(ref["frames"][0].at("flip_mean").get<double>(), expected.mean, 1e-9);
    EXPECT_EQ(ref["frames"][0].at("flip").at("exposures").get<uint32_t>(), expected.exposureCount);
    EXPECT_GT(expected.mean, 0.0);
    double bandSum = 0;  // the bands' means weighted by their pixels give the image's mean
    uint64_t pixels = 0;
    for (const auto& b : ref["frames"][0].at("bands")) {
        bandSum += b.at("flip_mean").get<double>() * double(b.at("pixels").get<uint64_t>());
        pixels += b.at("pixels").get<uint64_t>();
    }
    EXPECT_NEAR(bandSum / double(pixels), expected.mean, 1e-6);
    EXPECT_NEAR(ref.at("mean").at("flip_mean").get<double>(),
                0.5 * (ref["frames"][0].at("flip_mean").get<double>() +
                       ref["frames"][1].at("flip_mean").get<double>()),
                1e-12);

    r = runWithReference(tmp / "c", "2",
                         {"--reference", (tmp / "a" / "tm.ldr.frame0001.exr").string(),
                          "--reference-output", "tm.ldr", "--flip-ppd", "20"});
    ASSERT_EQ(r.code, 0) << r.describe();
    const json ldr = reportOf(tmp / "c").at("reference");
    EXPECT_EQ(ldr.at("flip").at("mode"), "ldr");
    EXPECT_EQ(ldr.at("flip").at("pixels_per_degree").get<double>(), 20.0);
    r = runWithReference(tmp / "d", "2", {"--reference", reference.string(), "--no-flip"});
    ASSERT_EQ(r.code, 0) << r.describe();
    EXPECT_FALSE(reportOf(tmp / "d").at("reference").at("mean").contains("flip_mean"));

    expectInputError(runWithReference(tmp / "e", "1", {"--flip-mode", "ldr"}),
                     {"--flip-mode", "needs --reference"});
    expectInputError(runWithReference(tmp / "f", "1",
                                      {"--reference", reference.string(), "--flip-ppd", "monitor"}),
                     {"--flip-ppd", "camera"});
}

TEST(CliReference, BadReferencesAreInputErrors) {
    TempDir tmp;
    ImageRGBA small{16, 16, std::vector<float>(16 * 16 * 4, 0.5f)};
    fovea::image::writeExr(tmp / "small.exr", small);
    expectInputError(
        runWithReference(tmp / "o1", "1", {"--reference", (tmp / "small.exr").string()}),
        {(tmp / "small.exr").string(), "16x16", "32x32"});
    expectInputError(
        runWithReference(tmp / "o2", "1", {"--reference", (tmp / "nope.exr").string()}),
        {"--reference", (tmp / "nope.exr").string(), "does not exist"});
    ImageRGBA nan{32, 32, std::vector<float>(32 * 32 * 4, 0.5f)};
    nan.pixels[(5 * 32 + 3) * 4 + 1] = std::numeric_limits<float>::quiet_NaN();
    fovea::image::writeExr(tmp / "nan.exr", nan);
    expectInputError(runWithReference(tmp / "o3", "1", {"--reference", (tmp / "nan.exr").string()}),
                     {(tmp / "nan.exr").string(), "NaN"});
    fs::create_directories(tmp / "dir");
    fovea::image::writeExr(tmp / "dir" / "x.frame0000.exr", nan);
    expectInputError(runWithReference(tmp / "o4", "2", {"--reference", (tmp / "dir").string()}),
                     {"--reference", "frame 1", "frame0001"});
    fs::create_directories(tmp / "two");
    fovea::image::writeExr(tmp / "two" / "x.frame0000.exr", nan);
    fovea::image::writeExr(tmp / "two" / "y.frame0000.exr", nan);
    expectInputError(
        runWithReference(tmp / "o7", "1", {"--reference", (tmp / "two").string()}),
        {"--reference", "2 files for frame 0", "x.frame0000.exr", "pt.radiance.frameNNNN.exr"});
    ImageRGBA ok{32, 32, std::vector<float>(32 * 32 * 4, 0.5f)};
    fovea::image::writeExr(tmp / "ok.exr", ok);
    expectInputError(runWithReference(tmp / "o5", "1",
                                      {"--reference", (tmp / "ok.exr").string(),
                                       "--reference-output", "acc.meen"}),
                     {"--reference-output", "acc.meen", "did you mean 'acc.mean'"});
    expectInputError(runWithReference(tmp / "o6", "1", {"--reference-output", "acc.mean"}),
                     {"--reference-output", "needs --reference"});
    for (const char* out : {"o1", "o2", "o3", "o4", "o6", "o7"})
        EXPECT_FALSE(fs::exists(tmp / out / "report.json")) << out;
}
