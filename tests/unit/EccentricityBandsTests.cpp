// Error per eccentricity band (eval/metrics/EccentricityBands.h): eccentricities against the
// camera's field of view, band membership, per-band RMSE of errors placed in one band only, and
// per-eye gazes in stereo.
#include <gtest/gtest.h>

#include <cmath>

#include "eval/metrics/EccentricityBands.h"

using namespace fovea;
using eval::eccentricityBandErrors;
using eval::pixelEccentricityDegrees;

namespace {

scene::FrameCamera camera(uint32_t w, uint32_t h, bool stereo, glm::vec2 left,
                          glm::vec2 right = glm::vec2(0.5f)) {
    scene::CameraDesc desc;
    desc.yfov = 1.2f;  // ~68.8 degrees: bands 0-5, 5-20 and 20+ all exist
    scene::CameraRigOptions rig;
    rig.stereo = stereo;
    const glm::vec2 gaze[scene::kMaxEyes] = {left, right};
    return scene::makeFrameCamera(desc, w, h, rig, 0, nullptr, gaze);
}

image::ImageRGBA constant(uint32_t w, uint32_t h, float v) {
    image::ImageRGBA img;
    img.width = w;
    img.height = h;
    img.pixels.assign(size_t(w) * h * 4, v);
    return img;
}

}  // namespace

TEST(EccentricityBands, EccentricityFollowsTheFieldOfView) {
    auto cam = camera(64, 64, false, {0.5f, 0.5f});
    // Pixel centres next to the gaze: about half a pixel's angle.
    EXPECT_LT(pixelEccentricityDegrees(cam, 64, 64, 32, 32), 1.0);
    // The top row's centre: close to yfov / 2 = 34.4 degrees.
    EXPECT_NEAR(pixelEccentricityDegrees(cam, 64, 64, 32, 0), 34.38, 0.8);
    // Symmetric about the gaze.
    EXPECT_NEAR(pixelEccentricityDegrees(cam, 64, 64, 10, 31),
                pixelEccentricityDegrees(cam, 64, 64, 53, 31), 1e-9);
}

TEST(EccentricityBands, ErrorsLandInTheirBand) {
    const uint32_t w = 96, h = 64;
    auto cam = camera(w, h, false, {0.3f, 0.6f});
    image::ImageRGBA ref = constant(w, h, 0.5f), test = ref;
    uint64_t counts[3] = {};
    for (uint32_t y = 0; y < h; ++y)
        for (uint32_t x = 0; x < w; ++x) {
            double e = pixelEccentricityDegrees(cam, w, h, x, y);
            int band = e < 5 ? 0 : (e < 20 ? 1 : 2);
            ++counts[band];
            if (band == 1)  // an error of 0.2 in R, G and B in the middle band only
                for (int c = 0; c < 3; ++c) test.pixels[(size_t(y) * w + x) * 4 + c] += 0.2f;
        }
    auto bands = eccentricityBandErrors(test, ref, cam);
    ASSERT_EQ(bands.size(), 3u);
    for (int b = 0; b < 3; ++b) {
        EXPECT_EQ(bands[b].pixels, counts[b]) << b;
        EXPECT_GT(bands[b].pixels, 0u) << b;
    }
    EXPECT_EQ(bands[0].rmse, 0.0);
    EXPECT_NEAR(bands[1].rmse, 0.2, 1e-6);
    EXPECT_EQ(bands[2].rmse, 0.0);
    EXPECT_EQ(bands[0].fromDegrees, 0.0);
    EXPECT_EQ(bands[1].fromDegrees, 5.0);
    EXPECT_EQ(bands[2].fromDegrees, 20.0);
    EXPECT_TRUE(std::isinf(bands[2].toDegrees));
    auto json = eval::bandErrorsToJson(bands);
    EXPECT_TRUE(json[2]["to"].is_null());
    EXPECT_DOUBLE_EQ(json[1]["rmse"].get<double>(), bands[1].rmse);
}

TEST(EccentricityBands, StereoUsesEachEyesGaze) {
    const uint32_t w = 128, h = 64;
    auto cam = camera(w, h, true, {0.25f, 0.5f}, {0.75f, 0.5f});
    // Each eye's gaze pixel is at eccentricity ~0, the other eye's gaze position is not.
    EXPECT_LT(pixelEccentricityDegrees(cam, w, h, 16, 32), 1.5);
    EXPECT_LT(pixelEccentricityDegrees(cam, w, h, 64 + 48, 32), 1.5);
    EXPECT_GT(pixelEccentricityDegrees(cam, w, h, 48, 32), 10.0);
}
