// `fovea compare TEST REFERENCE [--json]` end to end: the printed metrics match
// eval/metrics/ImageMetrics (and ꟻLIP, eval/flip) on images with known answers; missing files, size
// mismatches and NaN values exit 2 naming the file. CPU only (no device is created).
#include <limits>

#include "eval/flip/Flip.h"
#include "eval/metrics/ImageMetrics.h"
#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;
using fovea::image::ImageRGBA;

namespace {

ImageRGBA gradient(uint32_t w, uint32_t h, float offset) {
    ImageRGBA img;
    img.width = w;
    img.height = h;
    img.pixels.resize(size_t(w) * h * 4);
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            float* p = &img.pixels[(size_t(y) * w + x) * 4];
            p[0] = float(x) / float(w) + offset;
            p[1] = float(y) / float(h) + offset;
            p[2] = 0.5f + offset;
            p[3] = 1.0f;
        }
    return img;
}

}  // namespace

TEST(CliCompare, JsonHasEveryMetricWithKnownValues) {
    TempDir tmp;
    const float offset = 0.125f;
    ImageRGBA ref = gradient(24, 16, 0.0f), test = gradient(24, 16, offset);
    fovea::image::writeExr(tmp / "ref.exr", ref);
    fovea::image::writeExr(tmp / "test.exr", test);
    Result r = cli({"compare", (tmp / "test.exr").string(), (tmp / "ref.exr").string(), "--json"});
    ASSERT_EQ(r.code, 0) << r.describe();
    json j = json::parse(r.out, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << r.describe();
    EXPECT_EQ(j.at("size"), json::array({24, 16}));
    EXPECT_EQ(j.at("test"), (tmp / "test.exr").string());
    EXPECT_EQ(j.at("reference"), (tmp / "ref.exr").string());
    // A constant offset on every RGB value: RMSE = offset, PSNR = 20 log10(1 / offset).
    EXPECT_NEAR(j.at("rmse").get<double>(), offset, 1e-6);
    EXPECT_NEAR(j.at("mse").get<double>(), offset * offset, 1e-6);
    EXPECT_NEAR(j.at("rmse_percent").get<double>(), 100.0 * offset, 1e-4);
    EXPECT_NEAR(j.at("psnr_db").get<double>(), 20.0 * std::log10(1.0 / offset), 1e-4);
    EXPECT_NEAR(j.at("temporal_error").get<double>(), offset, 1e-6);
    EXPECT_EQ(j.at("peak").get<double>(), 1.0);
    EXPECT_EQ(j.at("rel_mse_epsilon").get<double>(), 1e-2);
    // relMSE and SSIM: the same numbers as the library on the images read back.
    fovea::eval::ImageMetrics m = fovea::eval::computeMetrics(
        fovea::image::readImage(tmp / "test.exr"), fovea::image::readImage(tmp / "ref.exr"));
    EXPECT_NEAR(j.at("rel_mse").get<double>(), m.relMse, 1e-9);
    EXPECT_NEAR(j.at("ssim").get<double>(), m.ssim, 1e-9);
    EXPECT_GT(m.ssim, 0.0);
    EXPECT_LT(m.ssim, 1.0);
}

TEST(CliCompare, IdenticalImagesTextAndJson) {
    TempDir tmp;
    fovea::image::writeExr(tmp / "a.exr", gradient(16, 16, 0.0f));
    Result r = cli({"compare", (tmp / "a.exr").string(), (tmp / "a.exr").string(), "--json"});
    ASSERT_EQ(r.code, 0) << r.describe();
    json j = json::parse(r.out, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << r.describe();
    EXPECT_EQ(j.at("rmse").get<double>(), 0.0);
    EXPECT_TRUE(j.at("psnr_db").is_null()) << "infinite PSNR is null in JSON";
    EXPECT_NEAR(j.at("ssim").get<double>(), 1.0, 1e-12);

    Result text = cli({"compare", (tmp / "a.exr").string(), (tmp / "a.exr").string()});
    ASSERT_EQ(text.code, 0) << text.describe();
    for (const char* row : {"RMSE", "RMSE %", "relMSE", "PSNR (dB)", "SSIM", "temporal error"})
        EXPECT_TRUE(contains(text.out, row)) << row << "\n" << text.describe();
    EXPECT_TRUE(contains(text.out, "inf")) << text.describe();
}

TEST(CliCompare, PeakAndEpsilonOptions) {
    TempDir tmp;
    fovea::image::writeExr(tmp / "r.exr", gradient(12, 12, 0.0f));
    fovea::image::writeExr(tmp / "t.exr", gradient(12, 12, 0.25f));
    Result a = cli({"compare", (tmp / "t.exr").string(), (tmp / "r.exr").string(), "--json"});
    Result b = cli({"compare", (tmp / "t.exr").string(), (tmp / "r.exr").string(), "--json",
                    "--peak", "10", "--epsilon", "1"});
    ASSERT_EQ(a.code, 0) << a.describe();
    ASSERT_EQ(b.code, 0) << b.describe();
    json ja = json::parse(a.out), jb = json::parse(b.out);
    EXPECT_NEAR(jb["psnr_db"].get<double>() - ja["psnr_db"].get<double>(), 20.0, 1e-6);
    EXPECT_LT(jb["rel_mse"].get<double>(), ja["rel_mse"].get<double>());
    EXPECT_EQ(jb["rel_mse_epsilon"].get<double>(), 1.0);
    expectInputError(
        cli({"compare", (tmp / "t.exr").string(), (tmp / "r.exr").string(), "--peak", "0"}),
        {"--peak"});
}

TEST(CliCompare, InputErrorsNameTheFile) {
    TempDir tmp;
    fovea::image::writeExr(tmp / "a.exr", gradient(16, 16, 0.0f));
    fovea::image::writeExr(tmp / "small.exr", gradient(8, 16, 0.0f));
    ImageRGBA bad = gradient(16, 16, 0.0f);
    bad.pixels[(5 * 16 + 7) * 4 + 2] = std::numeric_limits<float>::quiet_NaN();
    fovea::image::writeExr(tmp / "nan.exr", bad);
    const std::string a = (tmp / "a.exr").string();

    expectInputError(cli({"compare", a, (tmp / "missing.exr").string()}), {"missing.exr"});
    expectInputError(cli({"compare", (tmp / "missing.exr").string(), a}), {"missing.exr"});
    expectInputError(cli({"compare", a, (tmp / "small.exr").string()}),
                     {"small.exr", "8x16", "16x16"});
    expectInputError(cli({"compare", (tmp / "nan.exr").string(), a, "--json"}),
                     {"nan.exr", "(7, 5)", "NaN"});
    expectInputError(cli({"compare", a}), {"reference"});  // missing positional
}

// ꟻLIP through `compare`: the same figure as the library, HDR for an EXR reference and LDR for a
// PNG unless --flip-mode says otherwise, the settings in "flip", the map written where asked and
// never over an existing file without --overwrite.
TEST(CliCompare, FlipMeanModeAndMap) {
    TempDir tmp;
    ImageRGBA ref = gradient(24, 16, 0.0f), test = gradient(24, 16, 0.125f);
    fovea::image::writeExr(tmp / "ref.exr", ref);
    fovea::image::writeExr(tmp / "test.exr", test);
    fovea::image::writePng(tmp / "ref.png", ref, fovea::image::PngEncoding::AsIs);
    fovea::image::writePng(tmp / "test.png", test, fovea::image::PngEncoding::AsIs);
    const std::string map = (tmp / "map.exr").string();
    Result r = cli({"compare", (tmp / "test.exr").string(), (tmp / "ref.exr").string(), "--json",
                    "--flip-map", map});
    ASSERT_EQ(r.code, 0) << r.describe();
    json j = json::parse(r.out, nullptr, false);
    ASSERT_FALSE(j.is_discarded()) << r.describe();
    fovea::eval::FlipOptions hdr;
    const fovea::eval::FlipResult expected = fovea::eval::computeFlip(
        fovea::image::readImage(tmp / "test.exr"), fovea::image::readImage(tmp / "ref.exr"), hdr);
    EXPECT_NEAR(j.at("flip_mean").get<double>(), expected.mean, 1e-9);
    EXPECT_GT(expected.mean, 0.0);
    EXPECT_EQ(j.at("flip").at("mode"), "hdr");
    EXPECT_EQ(j.at("flip").at("exposures").get<uint32_t>(), expected.exposureCount);
    EXPECT_NEAR(j.at("flip").at("pixels_per_degree").get<double>(), 67.0206, 1e-3);
    EXPECT_TRUE(j.contains("rmse"));  // every metric, ꟻLIP among them
    const ImageRGBA written = fovea::image::readImage(map);
    ASSERT_EQ(written.width, 24u);
    EXPECT_EQ(written.pixels[(3 * 24 + 5) * 4], expected.errors[3 * 24 + 5]);

    // The map exists now: refused without --overwrite, replaced with it.
    expectInputError(cli({"compare", (tmp / "test.exr").string(), (tmp / "ref.exr").string(),
                          "--flip-map", map}),
                     {"--flip-map", "map.exr", "--overwrite"});
    EXPECT_EQ(cli({"compare", (tmp / "test.exr").string(), (tmp / "ref.exr").string(), "--flip-map",
                   map, "--overwrite"})
                  .code,
              0);

    // PNG: LDR by the file type; --flip gives only ꟻLIP; --ppd changes the figure.
    r = cli(
        {"compare", (tmp / "test.png").string(), (tmp / "ref.png").string(), "--flip", "--json"});
    ASSERT_EQ(r.code, 0) << r.describe();
    j = json::parse(r.out, nullptr, false);
    EXPECT_EQ(j.at("flip").at("mode"), "ldr");
    EXPECT_FALSE(j.contains("rmse"));
    EXPECT_FALSE(j.at("flip").contains("exposures"));
    const double ldrMean = j.at("flip_mean").get<double>();
    r = cli({"compare", (tmp / "test.png").string(), (tmp / "ref.png").string(), "--flip", "--json",
             "--ppd", "10"});
    ASSERT_EQ(r.code, 0) << r.describe();
    EXPECT_NE(json::parse(r.out).at("flip_mean").get<double>(), ldrMean);
    // --flip-mode hdr on PNGs, and --no-flip leaves the key out.
    r = cli({"compare", (tmp / "test.png").string(), (tmp / "ref.png").string(), "--json",
             "--flip-mode", "hdr"});
    EXPECT_EQ(json::parse(r.out).at("flip").at("mode"), "hdr");
    r = cli({"compare", (tmp / "test.png").string(), (tmp / "ref.png").string(), "--json",
             "--no-flip"});
    ASSERT_EQ(r.code, 0) << r.describe();
    EXPECT_FALSE(json::parse(r.out).contains("flip_mean"));
    r = cli({"compare", (tmp / "test.png").string(), (tmp / "ref.png").string()});
    EXPECT_TRUE(contains(r.out, "LDR-ꟻLIP mean")) << r.describe();
}

TEST(CliCompare, FlipOptionErrorsNameTheOption) {
    TempDir tmp;
    fovea::image::writeExr(tmp / "a.exr", gradient(16, 16, 0.0f));
    fovea::image::writePng(tmp / "a.png", gradient(16, 16, 0.0f), fovea::image::PngEncoding::AsIs);
    const std::string a = (tmp / "a.exr").string(), p = (tmp / "a.png").string();
    expectInputError(cli({"compare", a, a, "--flip-map", (tmp / "map.tif").string()}),
                     {"--flip-map", ".exr or .png"});
    expectInputError(cli({"compare", a, a, "--flip-map", (tmp / "no" / "map.exr").string()}),
                     {"--flip-map", "does not exist"});
    expectInputError(cli({"compare", a, a, "--ppd", "0"}), {"--ppd"});
    expectInputError(cli({"compare", a, a, "--ppd", "nan"}), {"--ppd"});
    expectInputError(cli({"compare", a, a, "--flip-mode", "sdr"}), {"--flip-mode"});
    expectInputError(cli({"compare", a, a, "--flip", "--no-flip"}), {"--no-flip"});
    expectInputError(cli({"compare", a, a, "--start-exposure", "3", "--stop-exposure", "1"}),
                     {"start exposure", "stop exposure"});
    expectInputError(cli({"compare", p, p, "--start-exposure", "1"}),
                     {"--start-exposure", "HDR-ꟻLIP only"});
    EXPECT_FALSE(fs::exists(tmp / "map.tif"));
}
