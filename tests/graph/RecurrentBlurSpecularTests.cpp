// GPU tests of RecurrentBlur{signal: specular} on the ReBLUR rig (issue 26; seed 004 "Cooking
// specular denoiser"): a mirror (roughness 0) is not blurred spatially while a rough lobe is,
// about as much as the diffuse signal at roughness 1. NaN/Inf and the stereo seam:
// RecurrentBlurBothSignals in RecurrentBlurTests.cpp; the formulas:
// RecurrentBlurSpecularOracleTests.cpp; reflection ghosting:
// RecurrentBlurSpecularGhostingTests.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/graph/GpuTestFixture.h"
#include "tests/graph/RecurrentBlurRig.h"

using namespace fovea;
using fovea::test::Image;
using fovea::test::noise;
using fovea::test::ReblurRig;

namespace {

class RecurrentBlurSpecularTest : public GpuTest {};

double variance(const Image& img) {
    double s = 0, s2 = 0;
    size_t n = 0;
    for (size_t i = 0; i < img.size(); i += 4) {
        s += img[i];
        s2 += double(img[i]) * img[i];
        ++n;
    }
    const double m = s / double(n);
    return s2 / double(n) - m * m;
}

// One noisy frame through the spatial blur alone (no pre-blur, no history): a mirror keeps its
// pixels (radius 0: seed 004 sharp reflections), a roughness-1 lobe is blurred like the diffuse
// signal, and an intermediate roughness in between.
TEST_F(RecurrentBlurSpecularTest, MirrorIsNotBlurredRoughLobeIs) {
    const int w = 24, h = 24;
    const Image in = noise(w, h, 11);
    auto blurredVariance = [&](float roughness, const char* signal) {
        const std::string t = std::string(R"({ "signal": ")") + signal +
                              R"(", "prepassBlurRadius": 0, "maxBlurRadius": 6 })";
        const std::string s =
            std::string(R"({ "signal": ")") + signal + R"(", "maxBlurRadius": 6 })";
        ReblurRig rig(ctx(), w, h, t, s, false);
        rig.init();
        if (std::string(signal) == "specular") rig.setRoughness(roughness);
        rig.setGeometry(test::facingPlane(w, h, 5.0f));
        rig.frame(in);
        const Image out = rig.get("rbs.blurred");
        if (roughness == 0.0f && std::string(signal) == "specular") {
            for (size_t i = 0; i < out.size(); ++i) {
                if (i % 4 != 3) {
                    EXPECT_EQ(out[i], in[i]) << "mirror pixel " << i / 4;
                }
            }
        }
        return variance(out);
    };
    const double original = variance(in);
    const double mirror = blurredVariance(0.0f, "specular");
    const double glossy = blurredVariance(0.3f, "specular");
    const double rough = blurredVariance(1.0f, "specular");
    const double diffuse = blurredVariance(1.0f, "diffuse");
    EXPECT_EQ(mirror, original);
    EXPECT_LT(glossy, original);
    EXPECT_LT(rough, glossy);
    EXPECT_LT(rough, 0.5 * original);
    // Roughness 1 blurs about as much as the diffuse signal (same radius; the kernel plane and
    // weights differ in detail).
    EXPECT_LT(rough, 2.0 * diffuse);
    EXPECT_GT(rough, 0.5 * diffuse);
}

}  // namespace
