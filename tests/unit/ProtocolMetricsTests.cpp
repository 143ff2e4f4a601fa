// The evaluation protocol's figures (docs/benchmarks.md "the paper's protocol"): the error per
// foveation layer (eval/metrics/EccentricityBands.h) against an independent CPU computation on
// a synthetic stereo image, the noise-floor correction and the Pareto front selection
// (eval/metrics/ImageMetrics.h) on synthetic points.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "eval/metrics/ImageMetrics.h"
#include "eval/metrics/EccentricityBands.h"

using namespace fovea;

namespace {

scene::FrameCamera stereoCamera(uint32_t w, uint32_t h, glm::vec2 left, glm::vec2 right) {
    scene::CameraDesc desc;
    desc.yfov = 1.0f;
    scene::CameraRigOptions rig;
    rig.stereo = true;
    const glm::vec2 gaze[scene::kMaxEyes] = {left, right};
    return scene::makeFrameCamera(desc, w, h, rig, 0, nullptr, gaze);
}

image::ImageRGBA randomImage(uint32_t w, uint32_t h, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    image::ImageRGBA img;
    img.width = w;
    img.height = h;
    img.pixels.resize(size_t(w) * h * 4);
    for (float& v : img.pixels) v = u(rng);
    return img;
}

}  // namespace

TEST(ProtocolMetrics, PerLayerErrorMatchesACpuComputation) {
    // 2 x 48 x 40 side by side, gazes off centre and different per eye, radii 6 / 14 px: all
    // three layers have pixels in both eyes.
    const uint32_t w = 96, h = 40, eyeW = 48;
    const glm::vec2 gaze[2] = {{0.3f, 0.4f}, {0.7f, 0.6f}};
    auto cam = stereoCamera(w, h, gaze[0], gaze[1]);
    const image::ImageRGBA test = randomImage(w, h, 1), ref = randomImage(w, h, 2);
    eval::LayerRadii radii;
    radii.r0 = 6;
    radii.r1 = 14;
    // The oracle: FoveationMask's rule written out (foveation_mask.comp layerOf), d = distance of
    // the pixel centre to gaze * eye size in the pixel's eye.
    double sum[3] = {};
    uint64_t count[3] = {};
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            const uint32_t eye = x / eyeW;
            const double dx = (x - eye * eyeW + 0.5) - gaze[eye].x * eyeW;
            const double dy = (y + 0.5) - gaze[eye].y * h;
            const double d = std::sqrt(dx * dx + dy * dy);
            const int layer = d <= 6 ? 0 : (d <= 14 ? 1 : 2);
            EXPECT_EQ(eval::foveationLayerOf(cam, w, h, x, y, radii), uint32_t(layer))
                << x << "," << y;
            for (int c = 0; c < 3; ++c) {
                const double e = double(test.pixels[(size_t(y) * w + x) * 4 + c]) -
                                 ref.pixels[(size_t(y) * w + x) * 4 + c];
                sum[layer] += e * e;
            }
            ++count[layer];
        }
    const auto layers = eval::foveationLayerErrors(test, ref, cam, radii);
    ASSERT_EQ(layers.size(), 3u);
    for (int l = 0; l < 3; ++l) {
        ASSERT_GT(count[l], 0u) << l;
        EXPECT_EQ(layers[l].pixels, count[l]) << l;
        // The code subtracts in float (the images' precision), the oracle in double.
        EXPECT_NEAR(layers[l].rmse, std::sqrt(sum[l] / (3.0 * count[l])), 1e-6) << l;
    }
    EXPECT_EQ(layers[1].fromDegrees, 6.0);
    EXPECT_EQ(layers[2].fromDegrees, 14.0);
    const auto json = eval::layerErrorsToJson(layers, radii);
    EXPECT_EQ(json[0]["layer"], "fovea");
    EXPECT_EQ(json[2]["layer"], "outer");
    EXPECT_EQ(json[1]["unit"], "pixels");
    EXPECT_TRUE(json[2]["to"].is_null());
    // An error placed in the middle layer only shows there.
    image::ImageRGBA shifted = ref;
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x)
            if (eval::foveationLayerOf(cam, w, h, x, y, radii) == 1)
                for (int c = 0; c < 3; ++c) shifted.pixels[(size_t(y) * w + x) * 4 + c] += 0.25f;
    const auto only = eval::foveationLayerErrors(shifted, ref, cam, radii);
    EXPECT_EQ(only[0].rmse, 0.0);
    EXPECT_NEAR(only[1].rmse, 0.25, 1e-6);
    EXPECT_EQ(only[2].rmse, 0.0);
    // Degrees: the layer follows the eccentricity of EccentricityBands.
    radii.degrees = true;
    radii.r0 = 5;
    radii.r1 = 12;
    for (uint32_t x = 0; x < w; x += 7) {
        const double e = eval::pixelEccentricityDegrees(cam, w, h, x, 20);
        EXPECT_EQ(eval::foveationLayerOf(cam, w, h, x, 20, radii),
                  e <= 5 ? 0u : (e <= 12 ? 1u : 2u));
    }
}

TEST(ProtocolMetrics, NoiseCorrectedRmseTakesOutHalfTheFloor) {
    // Error 0.05 against the truth, reference noise 0.03 (floor MSE 2 * 0.03^2): measured MSE
    // 0.05^2 + 0.03^2, corrected back to 0.05.
    EXPECT_NEAR(eval::noiseCorrectedRmse(0.05 * 0.05 + 0.03 * 0.03, 2 * 0.03 * 0.03), 0.05, 1e-12);
    EXPECT_DOUBLE_EQ(eval::noiseCorrectedRmse(0.0004, 0.0), 0.02);
    EXPECT_EQ(eval::noiseCorrectedRmse(0.0001, 0.001), 0.0) << "within the reference's noise";
}

TEST(ProtocolMetrics, ParetoFrontOfSyntheticPoints) {
    //            0    1    2    3    4    5    6
    // ms:       10    5   20    5   12   30   NaN
    // error:     2    4    1    4    3    1    0
    // 0: optimal (nothing faster is as accurate); 1 and 3: equal, both optimal; 2: optimal
    // (most accurate at 20); 4: beaten by 0; 5: beaten by 2 (same error, slower); 6: NaN.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const auto p = eval::paretoOptimal({10, 5, 20, 5, 12, 30, nan}, {2, 4, 1, 4, 3, 1, 0});
    EXPECT_EQ(p, (std::vector<bool>{true, true, true, true, false, false, false}));
    EXPECT_EQ(eval::paretoOptimal({1}, {1}), std::vector<bool>{true});
    EXPECT_TRUE(eval::paretoOptimal({}, {}).empty());
    // One point better in both beats every other one.
    EXPECT_EQ(eval::paretoOptimal({3, 1, 2}, {3, 1, 2}), (std::vector<bool>{false, true, false}));
}
