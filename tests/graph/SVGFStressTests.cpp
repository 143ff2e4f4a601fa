// SVGF disocclusion and stress suite (issue 12; specs §1 F1-F5): a moving occluder restarts the
// pixels it reveals and leaves the others' history bit-exact; NaN/+-Inf in every input never
// reach the outputs or the history and are counted; a 1e4 firefly stays bounded and keeps the
// frame mean; a camera cut every frame restarts cleanly; a reprojection that rejects everything
// restarts every pixel; the history length is the weighted average of the kept taps (never the
// max), border pixels included.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "tests/graph/GpuTestFixture.h"
#include "tests/graph/SVGFTestUtil.h"

using namespace fovea;
using namespace fovea::testsvgf;

namespace {

class SVGFStress : public test::GpuTest {};

constexpr float kPlaneZ = 4.0f;
constexpr float kSpacing = 0.1f;  // world units between background pixels

// Background plane (z = 4, positions kSpacing apart: beyond positionThreshold 0.02 * 4 = 0.08, so
// the 3x3 fallback cannot borrow a neighbour's history) and an 8x8 occluder at z = 2 whose left
// edge is at `occX`, moving +2 px per frame (motion -2 on it, 0 elsewhere).
SVGFInputs occluderScene(int size, int occX, uint32_t colorSeed) {
    SVGFInputs in;
    in.resize(size, size);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const size_t i = in.at(x, y);
            const bool occ = occX >= 0 && x >= occX && x < occX + 8 && y >= 4 && y < 12;
            const float z = occ ? 2.0f : kPlaneZ;
            in.depth[i] = z;
            in.position[i + 0] = kSpacing * float(x) * (occ ? 0.5f : 1.0f) + (occ ? 100.0f : 0.0f);
            in.position[i + 1] = kSpacing * float(y);
            in.position[i + 2] = -z;
            in.position[i + 3] = 1.0f;
            in.normal[i + 2] = 1.0f;
            in.motion[i] = occ ? -2.0f : 0.0f;
            for (int c = 0; c < 3; ++c) in.albedo[i + size_t(c)] = 1.0f;
        }
    recolor(in, colorSeed);
    // The occluder's world position moves with it: its pixel k keeps its position.
    for (int y = 4; y < 12 && occX >= 0; ++y)
        for (int x = occX; x < occX + 8 && x < size; ++x)
            in.position[in.at(x, y)] = 100.0f + kSpacing * float(x - occX);
    return in;
}

bool covered(int x, int y, int occX) {
    return x >= occX && x < occX + 8 && y >= 4 && y < 12;
}

}  // namespace

TEST_F(SVGFStress, MovingOccluderRestartsRevealedPixelsAndKeepsTheRestBitExact) {
    const int size = 48, frames = 4;
    for (int tap : {0, 1}) {
        SVGFInputs a = occluderScene(size, 2, 1), b = occluderScene(size, -1, 1);
        const std::string params = R"({ "feedbackTap": )" + std::to_string(tap) + " }";
        SVGFHarness ha(ctx(), a, params), hb(ctx(), b, params);
        for (int f = 0; f < frames; ++f) {
            const int occX = 2 + 2 * f;
            a = occluderScene(size, occX, 10u + uint32_t(f));
            b = occluderScene(size, -1, 10u + uint32_t(f));
            ha.upload(a);
            hb.upload(b);
            ha.runFrame();
            hb.runFrame();
            auto accA = ha.read("accumulated"), accB = hb.read("accumulated");
            // A pixel's history is spatial with feedbackTap >= 1: per frame the filtered colour
            // of level 1 (radius 2), the 3x3 variance prefilter (1) and the spatial variance
            // (radius 3) reach 6 pixels further.
            const int reach = tap == 0 ? 0 : 6 * (f + 1);
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x) {
                    const size_t i = a.at(x, y);
                    if (f > 0 && covered(x, y, occX - 2) && !covered(x, y, occX)) {
                        ASSERT_EQ(accA[i + 3], 1.0f) << "revealed pixel restarts " << x << "," << y;
                    }
                    const bool near =
                        x >= 2 - reach && x < occX + 8 + reach && y >= 4 - reach && y < 12 + reach;
                    if (near) continue;
                    for (int c = 0; c < 4; ++c)
                        ASSERT_EQ(accA[i + size_t(c)], accB[i + size_t(c)])
                            << "untouched pixel " << x << "," << y << " tap " << tap;
                }
            // Only the 2 x 8 revealed pixels of each frame are rejected (cumulative counter).
            EXPECT_EQ(ha.stats()[2], 16u * uint32_t(f)) << "tap " << tap;
            EXPECT_EQ(hb.stats()[2], 0u);
        }
    }
}

TEST_F(SVGFStress, NanAndInfinityInEveryInputNeverReachTheOutputs) {
    const float bad[3] = {std::numeric_limits<float>::quiet_NaN(),
                          std::numeric_limits<float>::infinity(),
                          -std::numeric_limits<float>::infinity()};
    SVGFInputs in = randomScene(32, 32, 3);
    auto poison = [&](SVGFInputs& s) {
        int k = 0;
        for (auto* v :
             {&s.color, &s.position, &s.normal, &s.depth, &s.albedo, &s.emission, &s.motion})
            for (int j = 0; j < 3; ++j, ++k) (*v)[s.at(3 + 4 * k % 28, 2 + k)] = bad[j];
    };
    poison(in);
    SVGFHarness h(ctx(), in, "{}");
    for (int f = 0; f < 24; ++f) {
        recolor(in, 70u + uint32_t(f));
        poison(in);
        h.upload(in, true);
        h.runFrame();
        for (const char* field : {"filtered", "illumination", "accumulated"})
            ASSERT_TRUE(allFinite(h.read(field))) << field << " frame " << f;
        auto s = h.stats();
        EXPECT_EQ(s[0], 3u * uint32_t(f + 1)) << "3 non-finite colour samples per frame";
        EXPECT_GE(s[1], 9u) << "non-finite position, normal and depth pixels are counted";
    }
}

TEST_F(SVGFStress, FireflyStaysBoundedAndKeepsTheFrameMean) {
    // Specs §1 F5: a 1e4 firefly on a dark plane in the first frame (h = 1). Its variance says
    // "noise", so the filter spreads it (energy-preserving) instead of keeping a 1e4 dot; the
    // spread is bounded by the reach of the 7x7 spatial estimate (3 px) plus 3 levels
    // (2 * (1 + 2 + 4) = 14 px), and the frame mean stays within 2.5 % (the normalized
    // edge-stopping weights are not exactly mean-preserving: 2 % measured here, 0 % when the
    // old centre-only luminance test left the firefly unfiltered, issue 12).
    const int size = 48;
    SVGFInputs in = occluderScene(size, -1, 1);
    for (size_t i = 0; i < in.color.size(); ++i)
        if (i % 4 != 3) in.color[i] = 0.01f;
    in.color[in.at(24, 24)] = in.color[in.at(24, 24) + 1] = in.color[in.at(24, 24) + 2] = 1e4f;
    SVGFHarness h(ctx(), in, R"({ "iterations": 3 })");
    h.runFrame();
    auto out = h.read("illumination");
    double meanIn = 0.0, meanOut = 0.0, peak = 0.0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const size_t i = in.at(x, y);
            meanIn += in.color[i];
            meanOut += out[i];
            peak = std::max(peak, double(out[i]));
            if (std::max(std::abs(x - 24), std::abs(y - 24)) > 17) {
                ASSERT_NEAR(out[i], 0.01f, 1e-6f) << x << "," << y;
            }
            ASSERT_GE(out[i], 0.0f);
        }
    EXPECT_NEAR(meanOut / meanIn, 1.0, 0.025);
    // Spread, not kept: no pixel keeps more than 1 % of the firefly.
    EXPECT_LT(peak, 100.0);
}

TEST_F(SVGFStress, CameraCutEveryFrameRestartsCleanly) {
    SVGFInputs in = randomScene(32, 32, 4);
    in.color[in.at(7, 0)] = std::numeric_limits<float>::quiet_NaN();
    SVGFHarness h(ctx(), in, "{}");
    for (int f = 0; f < 4; ++f) {
        h.graph().reset();
        recolor(in, 50u + uint32_t(f));
        in.color[in.at(7, 0)] = std::numeric_limits<float>::quiet_NaN();
        h.upload(in, true);
        h.runFrame();
        auto acc = h.read("accumulated");
        ASSERT_TRUE(allFinite(acc) && allFinite(h.read("filtered")));
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                const size_t i = in.at(x, y);
                const float want = (in.depth[i] > 0.0f && !(x == 7 && y == 0)) ? 1.0f : 0.0f;
                ASSERT_EQ(acc[i + 3], want) << "h restarts at " << x << "," << y;
            }
        EXPECT_EQ(h.stats()[0], 1u) << "counters restart with the history";
        EXPECT_EQ(h.stats()[2], 0u) << "no history: nothing to reject";
    }
}

TEST_F(SVGFStress, AllRejectedReprojectionRestartsEveryPixel) {
    SVGFInputs in = randomScene(32, 32, 8);
    SVGFHarness h(ctx(), in, "{}");
    h.runFrame();
    uint32_t hits = 0;
    for (size_t i = 0; i < size_t(32) * 32; ++i) {
        in.motion[i * 4] = 1000.0f;  // every tap outside the image (3x3 fallback too)
        hits += in.depth[i * 4] > 0.0f;
    }
    recolor(in, 9);
    h.upload(in);
    h.runFrame();
    auto acc = h.read("accumulated");
    for (size_t i = 0; i < size_t(32) * 32; ++i)
        ASSERT_EQ(acc[i * 4 + 3], in.depth[i * 4] > 0.0f ? 1.0f : 0.0f) << i;
    EXPECT_EQ(h.stats()[2], hits);
    ASSERT_TRUE(allFinite(h.read("filtered")));
}

TEST_F(SVGFStress, HistoryLengthIsTheWeightedAverageOfTheKeptTaps) {
    // A plane with positions 0.01 apart (well inside positionThreshold 0.02 * 4): three frames
    // give h = 3 everywhere; in the 4th the left half (x < 8) is rejected (motion out of the
    // image), so h = 1 there and 4 on the right; in the 5th every pixel moves half a pixel
    // (motion +0.5): pixel 7 straddles taps 7 (h 1) and 8 (h 4) with weights 1/2 each.
    // Weighted average: 2.5 + 1 = 3.5 (a max would give 5, the nearest tap 2 or 5).
    const int size = 16;
    SVGFInputs in = occluderScene(size, -1, 1);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            in.position[in.at(x, y)] = 0.01f * float(x);
            in.position[in.at(x, y) + 1] = 0.01f * float(y);
        }
    SVGFHarness h(ctx(), in, "{}");
    for (int f = 0; f < 3; ++f) h.runFrame();
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < 8; ++x) in.motion[in.at(x, y)] = 1000.0f;
    h.upload(in);
    h.runFrame();
    auto acc = h.read("accumulated");
    ASSERT_EQ(acc[in.at(7, 5) + 3], 1.0f);
    ASSERT_EQ(acc[in.at(8, 5) + 3], 4.0f);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) in.motion[in.at(x, y)] = 0.5f;
    h.upload(in);
    h.runFrame();
    acc = h.read("accumulated");
    EXPECT_EQ(acc[in.at(7, 5) + 3], 3.5f);
    EXPECT_EQ(acc[in.at(3, 5) + 3], 2.0f);   // taps 3, 4 both h = 1
    EXPECT_EQ(acc[in.at(10, 5) + 3], 5.0f);  // taps 10, 11 both h = 4
    // The border pixel's second tap is outside the image: the kept one's weight is renormalized
    // (border pixels accumulate like the rest).
    EXPECT_EQ(acc[in.at(15, 5) + 3], 5.0f);
}

TEST_F(SVGFStress, HeavyTailedNoiseKeepsItsMean) {
    // Issue 12 (the forest came out 20-28 % darker than its input): a still plane whose
    // every frame has exactly 10 % of its pixels at 10 and the rest at 0 (mean 1, standard
    // deviation 3: few bright samples among dark ones, as 1 spp from many small lights). The
    // filtered mean stays within 5 % of 1 in each of 8 frames. Before the fix the spatial
    // variance estimate's absolute-scale luminance term and the centre-only (asymmetric)
    // luminance weight lost 49 % in the first frame and 19 % after 8.
    const int size = 64;
    SVGFInputs in = occluderScene(size, -1, 1);
    std::mt19937 rng(5);
    std::vector<size_t> order(size_t(size) * size);
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    SVGFHarness h(ctx(), in, "{}");
    for (int f = 0; f < 8; ++f) {
        std::shuffle(order.begin(), order.end(), rng);
        for (size_t k = 0; k < order.size(); ++k) {
            const float v = k < order.size() / 10 ? 10.0f : 0.0f;
            for (int c = 0; c < 3; ++c) in.color[order[k] * 4 + size_t(c)] = v;
            in.color[order[k] * 4 + 3] = 1.0f;
        }
        const double meanIn = 10.0 * double(order.size() / 10) / double(order.size());
        h.upload(in, true);
        h.runFrame();
        const auto out = h.read("illumination");
        double meanOut = 0.0;
        for (size_t i = 0; i < order.size(); ++i) meanOut += out[i * 4 + 1];
        meanOut /= double(order.size());
        EXPECT_NEAR(meanOut / meanIn, 1.0, 0.05) << "frame " << f;
    }
}
