// GPU tests of RecurrentBlur{signal: specular} on the ReBLUR rig (issue 26; seed 004 "Cooking
// specular denoiser"): NaN/Inf never become permanent in the specular chain, no tap crosses the
// stereo seam (the world-space kernel included), a mirror (roughness 0) is not blurred spatially
// while a rough lobe is, and a constant passes every stage unchanged. The formulas themselves:
// ReBLURSpecularOracleTests.cpp; reflection ghosting: ReBLURSpecularGhostingTests.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "tests/graph/ReBLURRig.h"
#include "tests/unit/GpuTestFixture.h"

using namespace fovea;
using fovea::test::Image;
using fovea::test::ReblurRig;

namespace {

class ReBLURSpecularTest : public GpuTest {};

const char* kSpecular = R"({ "signal": "specular" })";

Image noise(int w, int h, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Image img(size_t(w) * h * 4);
    for (size_t i = 0; i < img.size(); ++i) img[i] = i % 4 == 3 ? 1.0f : u(rng);
    return img;
}

bool allFinite(const Image& img) {
    return std::all_of(img.begin(), img.end(), [](float v) { return std::isfinite(v); });
}

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

TEST_F(ReBLURSpecularTest, NaNAndInfNeverBecomePermanent) {
    const int w = 16, h = 16;
    ReblurRig rig(ctx(), w, h, kSpecular, kSpecular, true);
    rig.init();
    rig.setRoughness(0.5f);
    const test::Geometry clean = test::facingPlane(w, h, 5.0f);
    rig.setGeometry(clean);
    const Image in = test::constantImage(w, h, 0.2f, 0.4f, 0.6f);
    for (int f = 0; f < 4; ++f) rig.frame(in);
    Image bad = in;
    test::Geometry badGeo = clean;
    const float nan = std::numeric_limits<float>::quiet_NaN(),
                inf = std::numeric_limits<float>::infinity();
    for (int k = 0; k < 4; ++k) {
        bad[(size_t(5 + k) * w + 7) * 4 + k % 3] = k % 2 ? inf : nan;
        badGeo.normal[(size_t(9) * w + 3 + k) * 4] = nan;
        badGeo.position[(size_t(2) * w + 3 + k) * 4 + 1] = inf;
    }
    std::vector<float> hit(size_t(w) * h, 1.0f);
    hit[size_t(8) * w + 8] = nan;
    hit[size_t(8) * w + 9] = inf;
    rig.setGeometry(badGeo);
    rig.frame(bad, hit);
    rig.setGeometry(clean);
    const char* outputs[] = {"rbt.preblurred", "rbt.accumulated", "rbt.hit",   "hf.result",
                             "rbs.blurred",    "rbs.history",     "rbs.result"};
    for (const char* o : outputs) EXPECT_TRUE(allFinite(rig.get(o))) << o << " (bad frame)";
    for (int f = 0; f < 40; ++f) rig.frame(in);
    for (const char* o : outputs) EXPECT_TRUE(allFinite(rig.get(o))) << o << " (40 frames later)";
    const Image out = rig.get("rbs.result");
    for (size_t i = 0; i < out.size(); ++i)
        if (i % 4 != 3) {
            ASSERT_NEAR(out[i], in[i], 0.05f) << "float " << i;
        }
}

TEST_F(ReBLURSpecularTest, TapsNeverCrossTheStereoSeam) {
    const int w = 32, h = 16;
    const char* params = R"({ "signal": "specular", "eyes": 2 })";
    ReblurRig rig(ctx(), w, h, params, params, true, R"({ "eyes": 2 })");
    rig.init();
    rig.setRoughness(1.0f);  // the widest kernel
    rig.setGeometry(test::facingPlane(w, h, 5.0f));
    Image in = test::constantImage(w, h, 0.0f, 0.0f, 0.0f);
    for (int y = 0; y < h; ++y)
        for (int x = w / 2; x < w; ++x)
            for (int k = 0; k < 3; ++k) in[(size_t(y) * w + x) * 4 + k] = 1.0f;
    Image motion(size_t(w) * h * 4, 0.0f);
    for (size_t i = 0; i < motion.size(); i += 4) motion[i] = 3.0f;
    for (int f = 0; f < 5; ++f) {
        if (f == 2) rig.setMotion(motion);
        rig.frame(in);
        for (const char* o : {"rbt.preblurred", "rbt.accumulated", "hf.result", "rbs.blurred",
                              "rbs.history", "rbs.result"}) {
            const Image out = rig.get(o);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w / 2; ++x)
                    for (int k = 0; k < 3; ++k)
                        ASSERT_EQ(out[(size_t(y) * w + x) * 4 + k], 0.0f)
                            << o << " " << x << "," << y;
        }
    }
}

// One noisy frame through the spatial blur alone (no pre-blur, no history): a mirror keeps its
// pixels (radius 0: seed 004 sharp reflections), a roughness-1 lobe is blurred like the diffuse
// signal, and an intermediate roughness in between.
TEST_F(ReBLURSpecularTest, MirrorIsNotBlurredRoughLobeIs) {
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
