// BMFR's variants (docs/passes/BMFR.md#variants): each difference between fovea's reading of P2 §3
// and the authors' OpenCL code (maZZZu/bmfr) is a named choice, and each is checked here:
// - the published fit (scaling, noise, mirrored edges, misses, clamp at 0) against a CPU port of
//   the authors' `fitter` + `weighted_sum` (tests/graph/BMFRPublishedOracle), one frame;
// - fitClamp = blockmax is the nonnegative fit clamped at the block's largest accumulated value;
// - the published block offsets are the authors' table in fovea's block-grid convention;
// - historyCount = unrounded weighs the new sample by the interpolated count (hand-worked case).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "core/sampling/BlockGrid.h"
#include "tests/graph/BMFRPublishedOracle.h"
#include "tests/graph/BMFRTestUtil.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::testbmfr;

namespace {

constexpr int kVariantSize = 64;  // 3x3 blocks with offsets (one more per axis than the image)

// A curved surface with a disc of misses (position, normal 0, as GBuffer writes them) and noisy
// positive colour, also at the misses (the oracle fits whatever the rows hold).
BMFRInputs variantScene() {
    BMFRInputs in;
    in.resize(kVariantSize, kVariantSize);
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> noise(-0.3f, 0.3f);
    for (int y = 0; y < kVariantSize; ++y)
        for (int x = 0; x < kVariantSize; ++x) {
            const size_t i = (size_t(y) * kVariantSize + x) * 4;
            // Block ranges above and below 1 unit: both branches of the published scaling.
            float w[3] = {0.06f * x, 0.02f * y, 0.4f * std::sin(0.2f * x) * std::cos(0.15f * y)};
            float n[3] = {0.3f * std::sin(0.1f * x + 1.0f), 0.3f * std::cos(0.13f * y), 1.0f};
            const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            const bool miss = (x - 48) * (x - 48) + (y - 20) * (y - 20) < 64;
            for (int c = 0; c < 3; ++c) {
                in.position[i + c] = miss ? 0.0f : w[c];
                in.normal[i + c] = miss ? 0.0f : n[c] / len;
                in.color[i + c] = std::max(0.0f, 1.0f + 0.5f * std::sin(2.0f * w[0] + float(c)) +
                                                     0.3f * w[2] + noise(rng));
            }
            in.position[i + 3] = miss ? 0.0f : 1.0f;
            in.normal[i + 3] = 1.0f;
            in.color[i + 3] = 1.0f;  // one sample
        }
    return in;
}

int mirrorIndex(int i, int size) {
    int m = i < 0 ? -i - 1 : (i >= size ? 2 * size - i - 1 : i);
    return std::clamp(m, 0, size - 1);
}

// The rows of block (bx, by) with grid offset `offset` as the chosen variant builds them.
testref::BMFRPublishedBlock variantBlock(const BMFRInputs& in, const std::vector<float>& normals,
                                         int bx, int by, const std::array<int, 2>& offset,
                                         bool mirror, bool fitMisses) {
    testref::BMFRPublishedBlock b;
    b.used.assign(testref::kPublishedBlockPixels, false);
    b.position.assign(testref::kPublishedBlockPixels * 3, 0.0);
    b.normal = b.target = b.position;
    for (int r = 0; r < testref::kPublishedBlockPixels; ++r) {
        int x = bx * 32 - offset[0] + r % 32, y = by * 32 - offset[1] + r / 32;
        const bool inside = x >= 0 && y >= 0 && x < kVariantSize && y < kVariantSize;
        if (!inside && !mirror) continue;
        x = mirrorIndex(x, kVariantSize);
        y = mirrorIndex(y, kVariantSize);
        const size_t i = (size_t(y) * kVariantSize + size_t(x)) * 4;
        if (in.position[i + 3] <= 0.0f && !fitMisses) continue;
        b.used[size_t(r)] = true;
        for (int c = 0; c < 3; ++c) {
            b.position[size_t(r) * 3 + c] = in.position[i + c];
            b.normal[size_t(r) * 3 + c] = normals[i + c];
            b.target[size_t(r) * 3 + c] = in.color[i + c];
        }
    }
    return b;
}

class BMFRVariantFitTest : public test::GpuTest,
                           public ::testing::WithParamInterface<std::tuple<bool, bool>> {};

}  // namespace

// One frame (phase I passes the colour through), the published table's frame-0 offset (30, 30):
// the first block row and column hold 30 rows outside the image, mirrored or absent.
TEST_P(BMFRVariantFitTest, PublishedFitMatchesTheCpuPortOfTheAuthorsCode) {
    const auto [mirror, fitMisses] = GetParam();
    const BMFRInputs in = variantScene();
    const std::string params = std::string(R"({ "variant": "published", "blockEdges": ")") +
                               (mirror ? "mirror" : "zero") + R"(", "misses": ")" +
                               (fitMisses ? "fit" : "skip") + R"(" })";
    BMFRHarness h(ctx(), in, params);
    const auto normals = h.normalsUsed();
    h.runFrame();
    const auto fitted = h.read("fitted");

    const auto offset = sampling::blockGridOffset(0, sampling::BlockGridTable::Published);
    ASSERT_EQ(offset[0], 30);
    double worst = 0.0, zmax = 0.0;
    int misses = 0, compared = 0;
    for (int by = 0; by < 3; ++by)
        for (int bx = 0; bx < 3; ++bx) {
            const auto block = variantBlock(in, normals, bx, by, offset, mirror, fitMisses);
            // With zero edges a corner block holds 4 rows and an edge block 64 rows spanning 2
            // pixel rows (w^2 affine in w there): underdetermined but for the noise, so any two
            // least-squares solvers may differ. Only determined blocks are compared.
            if (std::count(block.used.begin(), block.used.end(), true) < 256) continue;
            ++compared;
            const auto want = testref::bmfrPublishedFit(block, 0, 0.01f);
            for (int r = 0; r < testref::kPublishedBlockPixels; ++r) {
                const int x = bx * 32 - offset[0] + r % 32, y = by * 32 - offset[1] + r / 32;
                if (x < 0 || y < 0 || x >= kVariantSize || y >= kVariantSize) continue;
                const size_t i = (size_t(y) * kVariantSize + size_t(x)) * 4;
                const bool miss = in.position[i + 3] <= 0.0f;
                misses += miss;
                for (int c = 0; c < 3; ++c) {
                    // misses = skip: the pixel keeps its accumulated value (here the input).
                    const double expected =
                        miss && !fitMisses ? in.color[i + c] : want[size_t(r) * 3 + c];
                    worst = std::max(worst, std::fabs(double(fitted[i + c]) - expected));
                    zmax = std::max(zmax, double(in.color[i + c]));
                }
            }
        }
    EXPECT_EQ(compared, mirror ? 9 : 4);
    EXPECT_GT(misses, 100);
    // fp32 Householder QR on the GPU against Eigen's double QR of the same noisy system.
    EXPECT_LT(worst, 2e-3 * zmax) << "largest |GPU - CPU port| of the fitted value";
}

INSTANTIATE_TEST_SUITE_P(EdgesAndMisses, BMFRVariantFitTest,
                         ::testing::Combine(::testing::Bool(), ::testing::Bool()),
                         [](const auto& info) {
                             return std::string(std::get<0>(info.param) ? "Mirror" : "Zero") +
                                    (std::get<1>(info.param) ? "FitMisses" : "SkipMisses");
                         });

class BMFRVariantTest : public test::GpuTest {};

// fitClamp only bounds the published fit from above: blockmax = min(nonnegative, block max of z).
TEST_F(BMFRVariantTest, BlockMaxClampBoundsTheNonnegativeFit) {
    // A ramp that saturates (a knee) along x: [1, n, w, w^2] cannot bend that sharply, and the
    // least-squares fit overshoots the plateau (by ~9% for a quadratic in one dimension).
    BMFRInputs in = variantScene();
    for (int y = 0; y < kVariantSize; ++y)
        for (int x = 0; x < kVariantSize; ++x)
            for (int c = 0; c < 3; ++c)
                in.color[(size_t(y) * kVariantSize + x) * 4 + c] =
                    0.1f + std::min(0.15f * float((x + 30) % 32), 1.0f);
    auto fitWith = [&](const char* clamp) {
        BMFRHarness h(ctx(), in,
                      std::string(R"({ "variant": "published", "fitClamp": ")") + clamp + R"(" })");
        h.runFrame();
        return h.read("fitted");
    };
    const auto open = fitWith("nonnegative");
    const auto clamped = fitWith("blockmax");
    const auto offset = sampling::blockGridOffset(0, sampling::BlockGridTable::Published);
    int above = 0;
    for (int y = 0; y < kVariantSize; ++y)
        for (int x = 0; x < kVariantSize; ++x) {
            // The block's largest z over its (mirrored) rows: every row is an image pixel.
            const int bx = (x + offset[0]) / 32, by = (y + offset[1]) / 32;
            double zmax[3] = {0, 0, 0};
            for (int r = 0; r < 1024; ++r) {
                const int px = mirrorIndex(bx * 32 - offset[0] + r % 32, kVariantSize);
                const int py = mirrorIndex(by * 32 - offset[1] + r / 32, kVariantSize);
                for (int c = 0; c < 3; ++c)
                    zmax[c] = std::max(zmax[c],
                                       double(in.color[(size_t(py) * kVariantSize + px) * 4 + c]));
            }
            const size_t i = (size_t(y) * kVariantSize + size_t(x)) * 4;
            for (int c = 0; c < 3; ++c) {
                above += open[i + c] > zmax[c] * (1.0 + 1e-6);
                ASSERT_NEAR(clamped[i + c], std::min(double(open[i + c]), zmax[c]), 1e-5 * zmax[c])
                    << x << "," << y;
            }
        }
    EXPECT_GT(above, 0) << "the scene must make the open fit overshoot somewhere";
}

// The authors' BLOCK_OFFSETS (bmfr.cl; their kernel reads image pixel gid - 16 + o) partition the
// image exactly as kPublishedBlockGridOffsets does in fovea's convention, frame by frame.
TEST(BMFRVariantTable, PublishedOffsetsPartitionTheImageAsTheAuthorsTable) {
    const int authors[16][2] = {{-14, -14}, {4, -6},   {-8, 14}, {8, 0},    {-10, -8}, {2, 12},
                                {12, -12},  {-10, 0},  {12, 14}, {-8, -16}, {6, 6},    {-2, -2},
                                {6, -14},   {-16, 12}, {14, -4}, {-6, 4}};
    for (int f = 0; f < 16; ++f) {
        const auto ours = sampling::blockGridOffset(uint64_t(f) + 16u,  // the sequence repeats
                                                    sampling::BlockGridTable::Published);
        for (int axis = 0; axis < 2; ++axis) {
            // Block of pixel p: authors (p + 16 - o) / 32, ours (p + offset) / 32; the two must
            // differ by one constant (a renumbering) over the whole axis.
            const int shift = (0 + 16 - authors[f][axis]) / 32 - (0 + ours[size_t(axis)]) / 32;
            for (int p = 0; p < 700; ++p)
                ASSERT_EQ((p + 16 - authors[f][axis]) / 32 - (p + ours[size_t(axis)]) / 32, shift)
                    << "frame " << f << " axis " << axis << " pixel " << p;
        }
    }
}

// historyCount, worked by hand. Frame 0: colour 1 everywhere (count 1). Frame 1: only the right
// half is sampled, with colour 3 (mean 2, count 2); the left half keeps 1 (count 1). Frame 2:
// colour 0 everywhere, motion -0.5 px in x, so the first right-half pixel's history is the
// 50/50 mix of its left neighbour (1, n = 1) and itself (2, n = 2): 1.5 with n = 1.5.
// Published: weight 1 / (1.5 + 1) = 0.4 -> 0.9. Rounded first: n = 2, weight 1/3 -> 1.0.
// Both store the count round(1.5) + 1 = 3.
TEST_F(BMFRVariantTest, UnroundedCountWeighsTheNewSampleByTheInterpolatedCount) {
    constexpr int kW = 64, kH = 8, kBoundary = 32;
    auto run = [&](const char* count) {
        BMFRInputs in;
        in.resize(kW, kH);
        for (size_t p = 0; p < size_t(kW) * kH; ++p) {
            for (int c = 0; c < 3; ++c) in.normal[p * 4 + c] = c == 2 ? 1.0f : 0.0f;
            in.position[p * 4 + 2] = 5.0f;
            in.position[p * 4 + 3] = 1.0f;
            in.color[p * 4 + 0] = in.color[p * 4 + 1] = in.color[p * 4 + 2] = 1.0f;
            in.color[p * 4 + 3] = 1.0f;
        }
        BMFRHarness h(ctx(), in, std::string(R"({ "historyCount": ")") + count + R"(" })");
        h.runFrame();
        for (size_t p = 0; p < size_t(kW) * kH; ++p) {
            const bool right = int(p % kW) >= kBoundary;
            for (int c = 0; c < 3; ++c) in.color[p * 4 + c] = right ? 3.0f : 0.0f;
            in.color[p * 4 + 3] = right ? 1.0f : 0.0f;  // the left half is not sampled
        }
        h.upload(in);
        h.runFrame();
        for (size_t p = 0; p < size_t(kW) * kH; ++p) {
            for (int c = 0; c < 3; ++c) in.color[p * 4 + c] = 0.0f;
            in.color[p * 4 + 3] = 1.0f;
            in.motion[p * 4 + 0] = -0.5f;
        }
        h.upload(in);
        h.runFrame();
        return h.read("accumulated");
    };
    const auto published = run("unrounded");
    const auto rounded = run("rounded");
    const size_t i = (size_t(4) * kW + kBoundary) * 4;
    EXPECT_NEAR(published[i], 0.9f, 1e-5f);
    EXPECT_NEAR(rounded[i], 1.0f, 1e-5f);
    EXPECT_EQ(published[i + 3], 3.0f);
    EXPECT_EQ(rounded[i + 3], 3.0f);
    // Away from the boundary every tap has the same count: the two agree exactly.
    const size_t j = (size_t(4) * kW + 48) * 4;
    EXPECT_EQ(published[j], rounded[j]);
}

// `variant` sets every choice left at "variant"; a choice set by name wins over it.
TEST_F(BMFRVariantTest, VariantResolvesEveryChoiceAndNamedChoicesWin) {
    BMFRInputs in;
    in.resize(32, 32);
    using Choices = passes::BMFRPass::Choices;
    auto resolved = [&](const std::string& params) {
        BMFRHarness h(ctx(), in, params);
        return h.pass().choices();
    };
    auto bits = [](const Choices& c) {
        return std::vector<bool>{c.publishedOffsets, c.publishedScaling, c.mirrorEdges,
                                 c.fitMisses,        c.unroundedCount,   c.clampBlockMax};
    };
    // default: fovea's scaling and misses (measured better), the published rest.
    EXPECT_EQ(bits(resolved("{}")), (std::vector<bool>{true, false, true, false, true, false}));
    EXPECT_EQ(bits(resolved(R"({ "variant": "published" })")),
              (std::vector<bool>{true, true, true, true, true, false}));
    EXPECT_EQ(bits(resolved(R"({ "variant": "fovea" })")),
              (std::vector<bool>{false, false, false, false, false, true}));
    EXPECT_EQ(bits(resolved(R"({ "variant": "fovea", "featureScaling": "published",
                                  "misses": "fit" })")),
              (std::vector<bool>{false, true, false, true, false, true}));
    EXPECT_EQ(bits(resolved(R"({ "variant": "published", "offsetTable": "fovea",
                                  "fitClamp": "blockmax" })")),
              (std::vector<bool>{false, true, true, true, true, true}));
}
