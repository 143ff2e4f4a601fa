// SVGF against closed forms and its double-precision CPU twin (tests/graph/SVGFOracle.h):
// the exact running mean while 1/h >= alpha then the EMA (§4.1), the steady-state variance
// alpha/(2-alpha) sigma^2 of that EMA, one a-trous level with edge stopping off = the dilated
// B3-spline convolution (a delta gives the symmetric separable kernel), partition of unity, and
// GPU = oracle within 1e-4 on a random G-buffer for every feedbackTap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/util/Error.h"
#include "tests/graph/GpuTestFixture.h"
#include "tests/graph/SVGFOracle.h"
#include "tests/graph/SVGFTestUtil.h"

using namespace fovea;
using namespace fovea::testsvgf;

namespace {

// A flat plane facing the camera, one normal, every pixel a hit, colour `value` everywhere.
SVGFInputs flatScene(int size, float value) {
    SVGFInputs in;
    in.resize(size, size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const size_t i = in.at(x, y);
            in.depth[i] = 4.0f;
            in.position[i + 0] = 0.1f * float(x);
            in.position[i + 1] = 0.1f * float(y);
            in.position[i + 2] = -4.0f;
            in.position[i + 3] = 1.0f;
            in.normal[i + 2] = 1.0f;
            for (int c = 0; c < 3; ++c) {
                in.color[i + size_t(c)] = value;
                in.albedo[i + size_t(c)] = 1.0f;
            }
            in.color[i + 3] = 1.0f;
        }
    return in;
}

SVGFOracleFrame oracleFrame(const SVGFInputs& in, const std::vector<float>& normalUsed) {
    SVGFOracleFrame f;
    f.width = in.width;
    f.height = in.height;
    f.color = &in.color;
    f.normal = &normalUsed;
    f.depth = &in.depth;
    f.albedo = &in.albedo;
    f.emission = &in.emission;
    return f;
}

}  // namespace

// --- CPU: the oracle's own closed forms -------------------------------------------------------

TEST(SVGFOracle, RunningMeanWhileOneOverHAboveAlphaThenEma) {
    SVGFInputs in = flatScene(8, 0.0f);
    SVGFOracleParams p;
    p.feedbackTap = 0;  // colour history = unfiltered accumulation
    SVGFOracle o(p);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 2.0f);
    double mean = 0.0, ema = 0.0;
    for (int t = 1; t <= 12; ++t) {
        const float x = u(rng);
        for (size_t i = 0; i < 64; ++i)
            for (int c = 0; c < 3; ++c) in.color[i * 4 + size_t(c)] = x;
        o.frame(oracleFrame(in, in.normal));
        mean += (double(x) - mean) / t;
        ema = t <= 5 ? mean : ema + 0.2 * (double(x) - ema);  // 1/h >= 0.2 while h <= 5
        EXPECT_NEAR(o.accumulated()[9 * 4], ema, 1e-12) << "frame " << t;
        EXPECT_EQ(o.accumulated()[9 * 4 + 3], std::min(double(t), 32.0));
    }
}

TEST(SVGFOracle, OneLevelWithoutEdgeStoppingIsTheB3ConvolutionOfADelta) {
    const int w = 33, h = 33;
    SVGFInputs in = flatScene(w, 0.0f);
    SVGFOracleParams p;
    p.sigmaNormal = 0.0;       // normal term off
    p.sigmaLuminance = 1e300;  // luminance term off
    std::vector<double> img(size_t(w) * h * 4, 0.0);
    for (size_t i = 0; i < size_t(w) * h; ++i) img[i * 4 + 3] = 1.0;  // variance 1
    img[(size_t(16) * w + 16) * 4 + 0] = 1.0;                         // delta in red
    std::vector<char> data(size_t(w) * h, 1);
    const double b3[5] = {1.0 / 16, 1.0 / 4, 3.0 / 8, 1.0 / 4, 1.0 / 16};
    for (int level = 0; level < 3; ++level) {
        const int s = 1 << level;
        auto out = SVGFOracle::atrousLevel(p, w, h, img, in.normal, in.depth, data, level);
        double total = 0.0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const double v = out[(size_t(y) * w + x) * 4];
                total += v;
                // The response at pixel q to a delta at c is k(c - q) / sum of q's weights = k
                // (interior pixels: their 25 weights sum to 1): the B3 kernel, dilated by s.
                const int dx = 16 - x, dy = 16 - y;
                double want = 0.0;
                if (dx % s == 0 && dy % s == 0 && std::abs(dx / s) <= 2 && std::abs(dy / s) <= 2)
                    want = b3[dx / s + 2] * b3[dy / s + 2];
                EXPECT_NEAR(v, want, 1e-12) << "level " << level << " at " << x << "," << y;
                // Symmetric (catches offset typos such as (0,-2) for (0,-1)).
                EXPECT_NEAR(v, out[(size_t(32 - y) * w + (32 - x)) * 4], 1e-15);
                EXPECT_NEAR(v, out[(size_t(x) * w + y) * 4], 1e-15);
            }
        EXPECT_NEAR(total, 1.0, 1e-12);
        // A constant variance shrinks by sum k^2 = (35/128)^2 per level (specs §1: 0.0748).
        EXPECT_NEAR(out[(size_t(16) * w + 16) * 4 + 3], std::pow(35.0 / 128.0, 2), 1e-12);
    }
}

TEST(SVGFOracle, ConstantStaysConstantForAnySigma) {
    SVGFInputs in = randomScene(24, 24, 5);
    for (size_t i = 0; i < in.color.size(); ++i)
        if (i % 4 != 3) in.color[i] = 0.75f;
    for (double sl : {0.01, 4.0, 1e6})
        for (double sn : {0.0, 128.0})
            for (double sz : {0.0, 1.0}) {
                SVGFOracleParams p;
                p.sigmaLuminance = sl;
                p.sigmaNormal = sn;
                p.sigmaDepth = sz;
                SVGFOracle o(p);
                o.frame(oracleFrame(in, in.normal));
                for (size_t i = 0; i < size_t(24) * 24; ++i)
                    for (int c = 0; c < 3; ++c)
                        ASSERT_NEAR(o.illumination()[i * 4 + size_t(c)], 0.75, 1e-12);
            }
}

// --- GPU against closed forms ----------------------------------------------------------------

class SVGFGpu : public test::GpuTest {};

TEST_F(SVGFGpu, RunningMeanThenEmaOnTheGpu) {
    SVGFInputs in = flatScene(16, 0.0f);
    SVGFHarness h(ctx(), in, R"({ "feedbackTap": 0, "iterations": 1 })");
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(0.0f, 2.0f);
    double mean = 0.0, ema = 0.0, m2 = 0.0, mu1 = 0.0, mu2 = 0.0;
    for (int t = 1; t <= 9; ++t) {
        const float x = u(rng);
        for (size_t i = 0; i < 256; ++i)
            for (int c = 0; c < 3; ++c) in.color[i * 4 + size_t(c)] = x;
        h.upload(in, true);
        h.runFrame();
        mean += (double(x) - mean) / t;
        m2 += (double(x) * x - m2) / t;
        ema = t <= 5 ? mean : ema + 0.2 * (double(x) - ema);
        const double l = double(x);  // grey: luminance = x
        mu1 = t <= 5 ? mean : mu1 + 0.2 * (l - mu1);
        mu2 = t <= 5 ? m2 : mu2 + 0.2 * (l * l - mu2);
        auto acc = h.read("accumulated");
        auto ill = h.read("illumination");
        const size_t px = 8 * 16 + 8;  // interior: all 25 taps inside
        EXPECT_NEAR(acc[px * 4], ema, 1e-5) << "frame " << t;
        EXPECT_EQ(acc[px * 4 + 3], float(t));
        // Variance from the moments: spatial (x 4/h) while h < 4, then the temporal estimate,
        // shrunk by the single level's sum k^2 (constant over the image).
        double var = std::max(mu2 - mu1 * mu1, 0.0) * (t < 4 ? 4.0 / t : 1.0);
        EXPECT_NEAR(ill[px * 4 + 3], var * std::pow(35.0 / 128.0, 2), 1e-5) << "frame " << t;
    }
}

TEST_F(SVGFGpu, SteadyStateVarianceOfTheEmaIsAlphaOverTwoMinusAlpha) {
    // i.i.d. noise of variance sigma^2 per pixel and frame: after the running mean the EMA's
    // variance tends to alpha/(2-alpha) sigma^2 = 0.111 sigma^2 (9 effective frames).
    const int size = 64;
    SVGFInputs in = flatScene(size, 0.0f);
    SVGFHarness h(ctx(), in, R"({ "feedbackTap": 0, "iterations": 1 })");
    std::mt19937 rng(11);
    std::normal_distribution<float> noise(1.0f, 0.5f);  // sigma^2 = 0.25
    for (int t = 0; t < 40; ++t) {
        for (size_t i = 0; i < size_t(size) * size; ++i) {
            const float x = noise(rng);
            for (int c = 0; c < 3; ++c) in.color[i * 4 + size_t(c)] = x;
        }
        h.upload(in, true);
        h.runFrame();
    }
    auto acc = h.read("accumulated");
    double s = 0.0, s2 = 0.0;
    const double n = double(size) * size;
    for (size_t i = 0; i < size_t(n); ++i) {
        s += acc[i * 4];
        s2 += double(acc[i * 4]) * acc[i * 4];
    }
    const double var = s2 / n - (s / n) * (s / n);
    const double want = 0.2 / 1.8 * 0.25;
    EXPECT_NEAR(var / want, 1.0, 0.08) << "variance " << var << " want " << want;
    EXPECT_NEAR(s / n, 1.0, 0.02);
}

TEST_F(SVGFGpu, ConstantStaysConstantAndOutputStaysInsideItsTaps) {
    SVGFInputs in = randomScene(32, 32, 9);
    for (const char* params :
         {R"({ "sigmaLuminance": 0.01 })", R"({ "sigmaNormal": 0, "sigmaDepth": 0 })", "{}"}) {
        SVGFInputs cst = in;
        for (size_t i = 0; i < cst.color.size(); ++i)
            if (i % 4 != 3) cst.color[i] = 0.75f;
        SVGFHarness h(ctx(), cst, params);
        for (int f = 0; f < 2; ++f) h.runFrame();
        auto ill = h.read("illumination");
        for (size_t i = 0; i < ill.size(); ++i) {
            if (i % 4 != 3) {
                ASSERT_NEAR(ill[i], 0.75f, 1e-5) << params << " at " << i;
            }
        }
        // Random colours: every output is a convex combination, inside [min, max] of the input.
        SVGFHarness r(ctx(), in, params);
        r.runFrame();
        auto out = r.read("illumination");
        float lo = 1e30f, hi = -1e30f;
        for (size_t i = 0; i < in.color.size(); ++i)
            if (i % 4 != 3) lo = std::min(lo, in.color[i]), hi = std::max(hi, in.color[i]);
        for (size_t i = 0; i < out.size(); ++i)
            if (i % 4 != 3) {
                ASSERT_GE(out[i], lo - 1e-5f) << params;
                ASSERT_LE(out[i], hi + 1e-5f) << params;
            }
    }
}

// --- GPU = oracle ------------------------------------------------------------------------------

class SVGFGpuOracle : public test::GpuTest, public ::testing::WithParamInterface<int> {};

TEST_P(SVGFGpuOracle, RandomGBufferMatchesTheDoublePrecisionTwin) {
    const int tap = GetParam();
    SVGFInputs in = randomScene(32, 24, 21);
    SVGFHarness h(ctx(), in, R"({ "feedbackTap": )" + std::to_string(tap) + " }");
    const std::vector<float> normals = h.readFeed("normal");  // rgba16f-rounded, as the GPU
    const std::vector<float> albedo = h.readFeed("albedo");   // rgba16f-rounded too
    SVGFOracleParams p;
    p.feedbackTap = tap;
    SVGFOracle o(p);
    // 6 frames: h passes historyForVariance (spatial -> temporal variance) and 1/h < alpha.
    for (int f = 0; f < 6; ++f) {
        recolor(in, 100u + uint32_t(f));
        if (f == 3) in.color[in.at(5, 7) + 3] = 0.0f;  // one untraced pixel keeps its history
        h.upload(in, true);
        h.runFrame();
        SVGFOracleFrame frame = oracleFrame(in, normals);
        frame.albedo = &albedo;
        o.frame(frame);
        in.color[in.at(5, 7) + 3] = 1.0f;
        for (const char* field : {"accumulated", "illumination", "filtered"}) {
            auto gpu = h.read(field);
            const auto& cpu = std::string(field) == "accumulated"    ? o.accumulated()
                              : std::string(field) == "illumination" ? o.illumination()
                                                                     : o.filtered();
            double worst = 0.0;
            size_t at = 0;
            for (size_t i = 0; i < gpu.size(); ++i) {
                const double e =
                    std::fabs(double(gpu[i]) - cpu[i]) / std::max(1.0, std::fabs(cpu[i]));
                if (e > worst) worst = e, at = i;
            }
            EXPECT_LT(worst, 1e-4)
                << field << " frame " << f << " tap " << tap << " at pixel " << at / 4
                << " channel " << at % 4 << ": gpu " << gpu[at] << " oracle " << cpu[at];
        }
    }
}

INSTANTIATE_TEST_SUITE_P(EveryFeedbackTap, SVGFGpuOracle, ::testing::Values(0, 1, 2, 3, 4, 5));

TEST_F(SVGFGpu, FeedbackTapBeyondIterationsIsAClearError) {
    SVGFInputs in = flatScene(8, 1.0f);
    try {
        SVGFHarness h(ctx(), in, R"({ "iterations": 2, "feedbackTap": 3 })");
        FAIL() << "expected an error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/params/feedbackTap"), std::string::npos) << e.what();
    }
}

// Specs §1 oracle 6: once h >= historyForVariance (4) the variance pass leaves the accumulated
// colour bit-exact and only derives var = max(0, mu2 - mu1^2) from the moments; while h < 4 it
// replaces the colour by the spatial estimate. With iterations 1 the ping-pong image atrous_a
// still holds the variance pass's output after the frame.
TEST_F(SVGFGpu, VariancePassIsBitExactOnceTheHistoryIsLong) {
    const int size = 32;
    SVGFInputs in = randomScene(size, size, 4);
    SVGFHarness h(ctx(), in, R"({ "iterations": 1 })");
    for (int f = 0; f < 6; ++f) {
        recolor(in, 100u + uint32_t(f));
        h.upload(in, true);
        h.runFrame();
        const auto acc = h.read("accumulated");
        const auto var = h.read("atrous_a");
        const auto mom = h.read("hist_moments");
        int hits = 0, exact = 0;
        for (int i = 0; i < size * size; ++i) {
            const size_t k = size_t(i) * 4;
            if (!(acc[k + 3] > 0.0f)) continue;
            ++hits;
            bool same = true;
            for (int c = 0; c < 3; ++c) same = same && var[k + size_t(c)] == acc[k + size_t(c)];
            exact += same;
            if (acc[k + 3] >= 4.0f) {
                ASSERT_TRUE(same) << "pixel " << i << " frame " << f;
                const double want =
                    std::max(0.0, double(mom[k + 1]) - double(mom[k]) * double(mom[k]));
                ASSERT_NEAR(var[k + 3], want, 1e-5 * std::max(1.0, want)) << "pixel " << i;
            }
        }
        ASSERT_GT(hits, size * size / 2);
        // h = f + 1: the spatial path runs (and changes almost every colour) in frames 0-2.
        if (f < 3) {
            EXPECT_LT(exact, hits / 10) << "frame " << f;
        } else {
            EXPECT_EQ(exact, hits) << "frame " << f;
        }
    }
}
