// BMFR stress suite (issue 5): NaN/Inf/1e6/negative inputs never reach the history and are
// counted; zero albedo remodulates with albedo' = 1; far from the origin gives the same image;
// a long static accumulation saturates its counters without drift; a camera cut every frame
// restarts cleanly; the per-tap discard test rejects moved or turned surfaces. All outputs
// finite and bounded throughout.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/util/Error.h"
#include "tests/graph/BMFRTestUtil.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::testbmfr;

namespace {

constexpr int kStressSize = 32;

float truth(const float* w, int c) {
    return 1.0f + 0.3f * w[0] + 0.2f * w[1] * w[1] + 0.1f * float(c);
}

// A curved surface; colour = truth(position - shift) + uniform noise in [-0.5, 0.5].
BMFRInputs makeScene(float shift, uint32_t noiseSeed, int size = kStressSize) {
    BMFRInputs in;
    in.resize(size, size);
    std::mt19937 rng(noiseSeed);
    std::uniform_real_distribution<float> noise(-0.5f, 0.5f);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const size_t i = (size_t(y) * size + x) * 4;
            float w[3] = {0.05f * x, 0.05f * y, 0.3f * std::sin(0.2f * x) * std::cos(0.15f * y)};
            float n[3] = {0.3f * std::sin(0.1f * x), 0.3f * std::cos(0.13f * y), 1.0f};
            float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int c = 0; c < 3; ++c) {
                in.position[i + c] = w[c] + shift;
                in.normal[i + c] = n[c] / len;
                in.albedo[i + c] = 0.5f;
                in.color[i + c] = truth(w, c) + noise(rng);
            }
            in.position[i + 3] = in.normal[i + 3] = in.albedo[i + 3] = in.color[i + 3] = 1.0f;
        }
    return in;
}

void recolor(BMFRInputs& in, uint32_t noiseSeed) {
    std::mt19937 rng(noiseSeed);
    std::uniform_real_distribution<float> noise(-0.5f, 0.5f);
    for (size_t p = 0; p < size_t(in.width) * in.height; ++p) {
        float w[3] = {0.05f * float(p % size_t(in.width)), 0.05f * float(p / size_t(in.width)), 0};
        for (int c = 0; c < 3; ++c) in.color[p * 4 + c] = truth(w, c) + noise(rng);
    }
}

float maxAbs(const std::vector<float>& v) {
    float m = 0.0f;
    for (float x : v) m = std::max(m, std::fabs(x));
    return m;
}

class BMFRStressTest : public test::GpuTest {};

}  // namespace

// Both history precisions: with fp16 history the 1e6 firefly must saturate at 65504 (the
// largest half float), never become +Inf.
class BMFRBadInputTest : public test::GpuTest, public ::testing::WithParamInterface<bool> {};

TEST_P(BMFRBadInputTest, NonFiniteAndExtremeInputsNeverEnterHistory) {
    const bool fp16 = GetParam();
    BMFRInputs in = makeScene(0.0f, 1);
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    auto px = [&](int x, int y) { return (size_t(y) * kStressSize + x) * 4; };
    in.color[px(3, 3) + 0] = nan;  // non-finite colour x3
    in.color[px(10, 4) + 1] = inf;
    in.color[px(20, 20) + 2] = -inf;
    in.color[px(5, 25)] = 1e6f;         // a firefly (finite: kept)
    in.color[px(25, 5) + 1] = -5.0f;    // negative radiance x1
    in.position[px(12, 12) + 0] = nan;  // non-finite geometry x2
    in.normal[px(30, 30) + 2] = inf;
    BMFRHarness h(ctx(), in, fp16 ? R"({ "fp16History": true })" : "{}",
                  {.albedo = true, .emission = true, .motion = true});
    constexpr int kFrames = 5;
    for (int f = 0; f < kFrames; ++f) h.runFrame();
    for (const char* field : {"accumulated", "fitted", "filtered"}) {
        auto v = h.read(field);
        ASSERT_TRUE(allFinite(v)) << field;
        // Bounded by the largest finite input (the 1e6 firefly) and the count cap.
        EXPECT_LE(maxAbs(v), 1.0001e6f) << field;
    }
    // History slots are internal: what phase III saw last frame is the finite `filtered`.
    auto s = h.stats();
    EXPECT_EQ(s[0], 3u * kFrames) << "non-finite colour samples";
    EXPECT_EQ(s[1], 2u * kFrames) << "non-finite geometry pixels";
    EXPECT_EQ(s[2], 1u * kFrames) << "negative colour samples";
    auto acc = h.read("accumulated");
    EXPECT_EQ(acc[px(3, 3) + 0], 0.0f) << "no finite sample ever reached this pixel";
    EXPECT_EQ(acc[px(3, 3) + 3], 0.0f) << "count of a pixel without finite samples";
    EXPECT_EQ(acc[px(25, 5) + 1], 0.0f) << "negative radiance is clamped to 0";
    EXPECT_NEAR(acc[px(5, 25)], fp16 ? 65504.0f : 1e6f, 1.0f)
        << "a finite firefly is kept (saturated with fp16 history)";
}

INSTANTIATE_TEST_SUITE_P(HistoryPrecision, BMFRBadInputTest, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) {
                             return std::string(info.param ? "Fp16" : "Fp32");
                         });

TEST_F(BMFRStressTest, ZeroAlbedoRemodulatesWithOne) {
    BMFRInputs in = makeScene(0.0f, 2);
    for (size_t p = 0; p < size_t(kStressSize) * kStressSize; ++p)
        for (int c = 0; c < 3; ++c) {
            in.albedo[p * 4 + c] = (p % 2 == 0) ? 0.0f : 0.5f;
            in.emission[p * 4 + c] = 0.25f;
        }
    BMFRHarness h(ctx(), in, "{}", {.albedo = true, .emission = true, .motion = true});
    h.runFrame();  // no history: phase III passes the fit through
    auto fitted = h.read("fitted");
    auto out = h.read("filtered");
    ASSERT_TRUE(allFinite(out));
    for (size_t p = 0; p < size_t(kStressSize) * kStressSize; ++p)
        for (int c = 0; c < 3; ++c) {
            float albedo = (p % 2 == 0) ? 1.0f : 0.5f;  // albedo' of the contract
            ASSERT_NEAR(out[p * 4 + c], fitted[p * 4 + c] * albedo + 0.25f, 1e-5f) << p;
        }
}

class BMFRFarFromOriginTest : public test::GpuTest,
                              public ::testing::WithParamInterface<const char*> {};

TEST_P(BMFRFarFromOriginTest, GivesTheSameImage) {
    const std::string variant = GetParam();
    // 64 px: several blocks with moving offsets; 6 frames of fresh noise.
    auto render = [&](float shift) {
        BMFRInputs in = makeScene(shift, 3, 64);
        BMFRHarness h(ctx(), in, R"({ "variant": ")" + variant + R"(" })");
        for (int f = 0; f < 6; ++f) {
            recolor(in, 100 + uint32_t(f));
            h.upload(in, true);
            h.runFrame();
        }
        return h.read("filtered");
    };
    auto near = render(0.0f);
    auto far = render(1e4f);
    ASSERT_TRUE(allFinite(near));
    ASSERT_TRUE(allFinite(far));
    double worst = 0.0, sum2 = 0.0;
    for (size_t i = 0; i < near.size(); ++i) {
        if (i % 4 == 3) continue;
        double d = std::fabs(double(near[i]) - far[i]);
        worst = std::max(worst, d);
        sum2 += d * d;
    }
    const double rmse = std::sqrt(sum2 / (near.size() * 3 / 4));
    // Positions 1e4 from the origin carry ~1e-3 absolute rounding (fp32); with fovea's scaling
    // (centred before squaring) the images agree to that level. The published scaling squares
    // raw positions (1e8, where fp32 steps by 8) and then scales by the block range: measured
    // RMSE 6.3e-3 here, bounded but above fovea's; docs/passes/BMFR.md#variants.
    const bool fovea = variant == "fovea";
    EXPECT_LT(rmse, fovea ? 5e-3 : 2e-2) << "RMSE near vs far (values ~1-2)";
    EXPECT_LT(worst, fovea ? 5e-2 : 2e-1);
}

INSTANTIATE_TEST_SUITE_P(Variant, BMFRFarFromOriginTest, ::testing::Values("fovea", "published"));

TEST_F(BMFRStressTest, LongStaticAccumulationSaturatesWithoutDrift) {
    // 300 frames > the 255 count cap; the EMA regime starts after 4 (phase I) and 9 (phase III)
    // frames, so counters and weights have long been saturated (docs/passes/BMFR.md). The
    // issue's 10 000 frames take about 3 minutes on lavapipe, too long for CI: run them with
    // FOVEA_BMFR_LONG_FRAMES=10000 (docs/benchmarks.md records that run).
    BMFRInputs in = makeScene(0.0f, 4);
    BMFRHarness h(ctx(), in, "{}");
    const char* frames = std::getenv("FOVEA_BMFR_LONG_FRAMES");
    const int kFrames = frames ? std::max(300, std::atoi(frames)) : 300;
    for (int f = 0; f < kFrames; ++f) {
        recolor(in, 1000 + uint32_t(f));
        h.upload(in, true);
        h.runFrame();
    }
    auto acc = h.read("accumulated");
    auto out = h.read("filtered");
    ASSERT_TRUE(allFinite(acc));
    ASSERT_TRUE(allFinite(out));
    double bias = 0.0, err = 0.0;
    for (size_t p = 0; p < size_t(kStressSize) * kStressSize; ++p) {
        ASSERT_EQ(acc[p * 4 + 3], 255.0f) << "count saturates at 255";
        float w[3] = {0.05f * float(p % kStressSize), 0.05f * float(p / kStressSize), 0};
        for (int c = 0; c < 3; ++c) {
            double d = double(out[p * 4 + c]) - truth(w, c);
            bias += d;
            err += std::fabs(d);
        }
    }
    bias /= double(kStressSize * kStressSize * 3);
    err /= double(kStressSize * kStressSize * 3);
    // EMA with alpha 0.2 of U(-0.5, 0.5) noise keeps std ~0.1 in `accumulated`; the fit and the
    // second accumulation smooth it further. No drift: the mean error stays near zero.
    EXPECT_LT(std::fabs(bias), 0.02);
    EXPECT_LT(err, 0.06);
}

TEST_F(BMFRStressTest, CameraCutEveryFrameRestartsCleanly) {
    BMFRInputs in = makeScene(0.0f, 5);
    in.color[7 * 4] = std::numeric_limits<float>::quiet_NaN();
    BMFRHarness h(ctx(), in, "{}");
    for (int f = 0; f < 4; ++f) {
        h.graph().reset();
        recolor(in, 50 + uint32_t(f));
        in.color[7 * 4] = std::numeric_limits<float>::quiet_NaN();
        h.upload(in, true);
        h.runFrame();
        auto acc = h.read("accumulated");
        auto fitted = h.read("fitted");
        auto out = h.read("filtered");
        ASSERT_TRUE(allFinite(acc) && allFinite(fitted) && allFinite(out)) << "frame " << f;
        for (size_t p = 0; p < size_t(kStressSize) * kStressSize; ++p) {
            ASSERT_EQ(acc[p * 4 + 3], p == 7 ? 0.0f : 1.0f) << "count restarts, pixel " << p;
            for (int c = 0; c < 3; ++c)  // no history: phase III passes the fit through
                ASSERT_EQ(out[p * 4 + c], fitted[p * 4 + c]);
        }
        EXPECT_EQ(h.stats()[0], 1u) << "counters restart with the history";
    }
}

TEST_F(BMFRStressTest, DiscardTestRejectsMovedAndTurnedSurfaces) {
    BMFRInputs in = makeScene(0.0f, 6);
    BMFRHarness h(ctx(), in, "{}");
    h.runFrame();
    // Frame 2: the left third moves 1 unit (beyond positionThreshold 0.1), the bottom third
    // turns its normals around (cosine < normalThreshold 0.5); the rest is unchanged.
    for (int y = 0; y < kStressSize; ++y)
        for (int x = 0; x < kStressSize; ++x) {
            size_t i = (size_t(y) * kStressSize + x) * 4;
            if (x < 10) in.position[i + 2] += 1.0f;
            if (y >= 22)
                for (int c = 0; c < 3; ++c) in.normal[i + c] = -in.normal[i + c];
        }
    h.upload(in);
    h.runFrame();
    auto acc = h.read("accumulated");
    for (int y = 0; y < kStressSize; ++y)
        for (int x = 0; x < kStressSize; ++x) {
            float want = (x < 10 || y >= 22) ? 1.0f : 2.0f;
            ASSERT_EQ(acc[(size_t(y) * kStressSize + x) * 4 + 3], want) << x << "," << y;
        }
}

TEST_F(BMFRStressTest, AlbedoFeatureWithoutAlbedoInputIsAClearError) {
    BMFRInputs in = makeScene(0.0f, 7);
    try {
        BMFRHarness h(ctx(), in, R"({ "features": "albedo" })", {.albedo = false});
        FAIL() << "expected an error";
    } catch (const InputError& e) {
        // A compile-time input error (exit 2 in the CLI) that names the parameter's pointer.
        EXPECT_NE(std::string(e.what()).find("'albedo'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("/params/features"), std::string::npos) << e.what();
    }
    // With the input connected the albedo feature set runs (M = 13) and stays finite.
    BMFRHarness h(ctx(), in, R"({ "features": "albedo" })", {.albedo = true});
    h.runFrame();
    EXPECT_TRUE(allFinite(h.read("filtered")));
}
