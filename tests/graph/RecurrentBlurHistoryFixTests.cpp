// GPU tests of HistoryFix (seed 004, the ReBLUR talk; specs §2 HistoryFix oracles): pixels with
// N >= historyFixFrames come out bit-exact; just-disoccluded pixels (N = 0) of a noisy plane have
// a lower error with it than without (mips and stride); across a dark/bright depth edge the
// rebuilt dark pixels stay within 5 % of their own plane; the count can come from a separate
// input with an offset (BMFR: samples = N + 1); with albedo and emission connected a remodulated
// colour (BMFR's filtered) is rebuilt without mixing an emitter or a wall colour into coplanar
// neighbours (issue 13: HistoryFix after BMFR raised the error at a cut because of that); with
// normal connected it does not average across a crease of equal depth; clean normal-mapped shading
// and clean smooth detail survive a first frame (issue 13, FlightHelmet); historyFixFrames = 0 is
// a copy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "tests/graph/RecurrentBlurRig.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using fovea::test::Image;

namespace {

class HistoryFixTest : public GpuTest {};

// Feed.color/depth[/motion as count] -> HistoryFix.
class FixRig {
public:
    FixRig(gpu::Context& gpu, int w, int h, const std::string& params, bool separateCount = false,
           bool demodulate = false, bool withNormal = false)
        : mGpu(gpu), mGraph(gpu, test::reblurRegistry()), mW(w), mH(h) {
        std::string edges = R"({ "from": "feed.color", "to": "hf.color" },
                               { "from": "feed.depth", "to": "hf.depth" })";
        if (separateCount) edges += R"(, { "from": "feed.position", "to": "hf.count" })";
        if (demodulate)
            edges += R"(, { "from": "feed.albedo", "to": "hf.albedo" },
                          { "from": "feed.emission", "to": "hf.emission" })";
        if (withNormal) edges += R"(, { "from": "feed.normal", "to": "hf.normal" })";
        const std::string text =
            R"({ "version": 1, "name": "hf_test", "passes": [ { "name": "feed", "type": "Feed" },
               { "name": "hf", "type": "HistoryFix", "params": )" +
            test::ReblurRig::pixelSizes(params) + R"( } ], "edges": [ )" + edges +
            R"( ], "outputs": [ "hf.result" ] })";
        graph::CompileOptions o;
        o.width = uint32_t(w);
        o.height = uint32_t(h);
        mGraph.build(graph::parseGraphText(text, "hf_test"), o);
    }
    void setNormal(const Image& normal) { target("feed.normal").uploadRGBA32F(mGpu, normal); }
    void setGuides(const Image& albedo, const Image& emission) {
        target("feed.albedo").uploadRGBA32F(mGpu, albedo);
        target("feed.emission").uploadRGBA32F(mGpu, emission);
    }
    Image run(const Image& color, const Image& depth, const Image* count = nullptr) {
        target("feed.color").uploadRGBA32F(mGpu, color);
        target("feed.depth").uploadRGBA32F(mGpu, depth);
        if (count) target("feed.position").uploadRGBA32F(mGpu, *count);
        mGraph.runFrame();
        return mGraph.image("hf.result").downloadRGBA32F(mGpu);
    }

private:
    gpu::Image& target(const char* name) { return const_cast<gpu::Image&>(mGraph.image(name)); }
    gpu::Context& mGpu;
    graph::RenderGraph mGraph;
    int mW, mH;
};

// Noisy plane: value 0.5 + uniform noise of half-width `amp`, alpha = count(x, y).
template <class Count>
Image noisyPlane(int w, int h, float amp, uint32_t seed, Count count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-amp, amp);
    Image img(size_t(w) * h * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = &img[(size_t(y) * w + x) * 4];
            for (int k = 0; k < 3; ++k) p[k] = 0.5f + u(rng);
            p[3] = count(x, y);
        }
    return img;
}

bool inSquare(int x, int y) {
    return x >= 20 && x < 36 && y >= 20 && y < 36;
}

}  // namespace

// N >= 3 (and sky) pass bit-exactly; N < 3 pixels are changed. Both methods.
TEST_F(HistoryFixTest, EnoughHistoryIsBitExact) {
    const int w = 40, h = 32;
    const Image depth = test::facingPlane(w, h, 5.0f).depth;
    const Image in = noisyPlane(w, h, 0.3f, 3, [](int x, int y) { return float((x + 2 * y) % 6); });
    for (const char* method : {"mips", "stride"}) {
        FixRig rig(ctx(), w, h, std::string(R"({ "method": ")") + method + "\" }");
        const Image out = rig.run(in, depth);
        size_t changed = 0, low = 0;
        for (size_t i = 0; i < out.size(); i += 4) {
            if (in[i + 3] >= 3.0f) {
                for (int k = 0; k < 4; ++k)
                    ASSERT_EQ(out[i + k], in[i + k]) << method << " pixel " << i / 4;
            } else {
                ++low;
                changed += out[i] != in[i];
                EXPECT_EQ(out[i + 3], in[i + 3]) << "alpha passes through";
            }
        }
        EXPECT_GT(changed, low * 9 / 10) << method;
    }
}

// A disoccluded 16x16 square (N = 0, noise +-0.5) inside a converged plane (N = 30, noise
// +-0.02): the square's first-frame RMSE against the true 0.5 is lower after HistoryFix.
TEST_F(HistoryFixTest, DisoccludedFirstFrameErrorIsLower) {
    const int w = 56, h = 56;
    const Image depth = test::facingPlane(w, h, 5.0f).depth;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Image in(size_t(w) * h * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float* p = &in[(size_t(y) * w + x) * 4];
            const bool disoccluded = inSquare(x, y);
            for (int k = 0; k < 3; ++k) p[k] = 0.5f + (disoccluded ? 0.5f : 0.02f) * u(rng);
            p[3] = disoccluded ? 0.0f : 30.0f;
        }
    auto rmse = [&](const Image& img) {
        double sum = 0.0;
        int n = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                if (inSquare(x, y))
                    for (int k = 0; k < 3; ++k, ++n) {
                        const double d = img[(size_t(y) * w + x) * 4 + k] - 0.5;
                        sum += d * d;
                    }
        return std::sqrt(sum / n);
    };
    const double without = rmse(in);
    for (const char* method : {"mips", "stride"}) {
        FixRig rig(ctx(), w, h, std::string(R"({ "method": ")") + method + "\" }");
        const double with = rmse(rig.run(in, depth));
        EXPECT_LT(with, 0.5 * without) << method << ": " << with << " vs " << without;
    }
}

// Dark near plane (left, z = 3, 0.1) next to a bright far plane (right, z = 9, 1.0), a
// disoccluded band across the edge: the depth-aware upsample keeps every rebuilt dark pixel
// within 5 % of 0.1 (a plain mip would bleed the bright plane in).
TEST_F(HistoryFixTest, DepthEdgeDoesNotBleed) {
    const int w = 64, h = 32;
    std::vector<float> z(size_t(w) * h);
    Image in(size_t(w) * h * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool dark = x < 29;
            z[size_t(y) * w + x] = dark ? 3.0f : 9.0f;
            float* p = &in[(size_t(y) * w + x) * 4];
            p[0] = p[1] = p[2] = dark ? 0.1f : 1.0f;
            p[3] = x >= 16 && x < 44 ? 0.0f : 30.0f;
        }
    const Image depth = test::facingPlanes(w, h, z).depth;
    FixRig rig(ctx(), w, h, "{}");
    const Image out = rig.run(in, depth);
    for (int y = 0; y < h; ++y)
        for (int x = 16; x < 29; ++x)
            ASSERT_NEAR(out[(size_t(y) * w + x) * 4], 0.1f, 0.005f) << x << "," << y;
}

// The count from a separate input with countOffset 1 (BMFR: accumulated.a = samples = N + 1):
// samples 1..3 (N 0..2) are rebuilt, samples >= 4 pass; the colour's own alpha is ignored.
TEST_F(HistoryFixTest, SeparateCountWithOffset) {
    const int w = 32, h = 32;
    const Image depth = test::facingPlane(w, h, 5.0f).depth;
    const Image in = noisyPlane(w, h, 0.3f, 5, [](int, int) { return 1.0f; });
    const Image count = noisyPlane(w, h, 0.0f, 6, [](int x, int) { return float(1 + x % 6); });
    FixRig rig(ctx(), w, h, R"({ "countOffset": 1 })", true);
    const Image out = rig.run(in, depth, &count);
    for (size_t i = 0; i < out.size(); i += 4) {
        if (count[i + 3] >= 4.0f)
            ASSERT_EQ(out[i], in[i]) << "pixel " << i / 4;
        else
            ASSERT_NE(out[i], in[i]) << "pixel " << i / 4;
    }
}

// Resolution scale (issue 13): with referenceHeight 256 a 64-row image is 4x smaller, so the
// talk's levels 4, 3, 2 for N = 0, 1, 2 shift down by 2 to 2, 1, 0: N = 2 has no level left and
// passes bit-exactly, N = 0 and 1 are still rebuilt. The stride method's 7-px stride at N = 0
// becomes floor(14 / 4 / 2) = 1 px.
TEST_F(HistoryFixTest, ReferenceHeightShiftsTheLevel) {
    const int w = 64, h = 64;
    const Image depth = test::facingPlane(w, h, 5.0f).depth;
    const Image in = noisyPlane(w, h, 0.3f, 8, [](int x, int) { return float(x % 4); });
    FixRig rig(ctx(), w, h, R"({ "referenceHeight": 256 })");
    const Image out = rig.run(in, depth);
    int changed[4] = {0, 0, 0, 0}, total[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < out.size(); i += 4) {
        const int n = int(in[i + 3]);
        ++total[n];
        if (out[i] != in[i]) ++changed[n];
    }
    EXPECT_EQ(changed[2], 0);
    EXPECT_EQ(changed[3], 0);
    EXPECT_GT(changed[0], total[0] * 9 / 10);
    EXPECT_GT(changed[1], total[1] * 9 / 10);
}

// BMFR's filtered colour is y * albedo + emission (P2 §3.4). A noise-free y = 0.5 on one plane
// (N = 0 everywhere, as after a cut) with albedo stripes 0.2 / 0.8 and an emissive square (5.0)
// has nothing to rebuild: with albedo and emission connected both methods return the input
// (1e-4 relative), without them the coarse data mixes the emitter and the stripes into their
// coplanar neighbours (the depth test cannot see those edges) and some pixel moves by > 0.1.
TEST_F(HistoryFixTest, DemodulatedRebuildKeepsEmitterAndAlbedoEdges) {
    const int w = 48, h = 48;
    const Image depth = test::facingPlane(w, h, 5.0f).depth;
    Image albedo(size_t(w) * h * 4, 1.0f), emission(size_t(w) * h * 4, 0.0f), in(albedo.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = (size_t(y) * w + x) * 4;
            const float a = (x / 5) % 2 ? 0.8f : 0.2f;
            const float e = x >= 17 && x < 29 && y >= 17 && y < 29 ? 5.0f : 0.0f;
            for (int k = 0; k < 3; ++k) {
                albedo[i + k] = a;
                emission[i + k] = e;
                in[i + k] = 0.5f * a + e;
            }
            in[i + 3] = 0.0f;  // N = 0: every pixel is rebuilt
        }
    for (const char* method : {"mips", "stride"}) {
        const std::string params =
            std::string(R"({ "method": ")") + method + R"(", "referenceHeight": 0 })";
        FixRig plain(ctx(), w, h, params);
        const Image mixed = plain.run(in, depth);
        FixRig demod(ctx(), w, h, params, false, true);
        demod.setGuides(albedo, emission);
        const Image kept = demod.run(in, depth);
        float worstMixed = 0.0f;
        for (size_t i = 0; i < in.size(); i += 4)
            for (int k = 0; k < 3; ++k) {
                ASSERT_NEAR(kept[i + k], in[i + k], 1e-4f * in[i + k] + 1e-6f)
                    << method << " pixel " << i / 4;
                worstMixed = std::max(worstMixed, std::abs(mixed[i + k] - in[i + k]));
            }
        EXPECT_GT(worstMixed, 0.1f) << method << ": the test must see the mixing it guards against";
    }
}

// A crease of equal depth (a box's top and front face meet at the same depth): one plane in
// depth, the left part facing the camera (0.1), the right part turned by 90 degrees (1.0), every
// pixel N = 0. Depth alone accepts the bright side's texels, so dark pixels near the crease rise;
// with the normal connected (normalAngle 30) every rebuilt dark pixel stays within 5 % of 0.1.
TEST_F(HistoryFixTest, NormalKeepsACreaseOfEqualDepth) {
    const int w = 64, h = 32;
    test::Geometry g = test::facingPlane(w, h, 5.0f);
    Image in(size_t(w) * h * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = (size_t(y) * w + x) * 4;
            const bool dark = x < 29;
            if (!dark) {
                g.normal[i + 0] = 1.0f;  // turned by 90 degrees
                g.normal[i + 2] = 0.0f;
            }
            in[i] = in[i + 1] = in[i + 2] = dark ? 0.1f : 1.0f;
            in[i + 3] = 0.0f;
        }
    for (const char* method : {"mips", "stride"}) {
        const std::string params = std::string(R"({ "method": ")") + method + "\" }";
        FixRig plain(ctx(), w, h, params);
        const Image mixed = plain.run(in, g.depth);
        FixRig guided(ctx(), w, h, params, false, false, true);
        guided.setNormal(g.normal);
        const Image kept = guided.run(in, g.depth);
        float worstMixed = 0.0f;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < 29; ++x) {
                const size_t i = (size_t(y) * w + x) * 4;
                ASSERT_NEAR(kept[i], 0.1f, 0.005f) << method << " " << x << "," << y;
                worstMixed = std::max(worstMixed, mixed[i] - 0.1f);
            }
        EXPECT_GT(worstMixed, 0.05f) << method << ": depth alone must mix the crease";
    }
}

namespace {

// RMSE of the red channel of `out` against the clean input `truth`.
double rmseRed(const Image& out, const Image& truth) {
    double sum = 0.0;
    for (size_t i = 0; i < truth.size(); i += 4)
        sum += double(out[i] - truth[i]) * (out[i] - truth[i]);
    return std::sqrt(sum / double(truth.size() / 4));
}

}  // namespace

// Issue 13 (FlightHelmet under a sun): a clean first frame with normal-mapped shading — bands
// 2 px wide whose normals are tilted by +-12 degrees, lit 0.3 / 0.9 — must keep its shading. At
// normalAngle 30 the coarse texels that mix both bands (|n_L| = cos 12) were accepted and the
// bands were averaged away; at the default 10 degrees only the 2x2 texels of the pixel's own band
// are used.
TEST_F(HistoryFixTest, NormalMappedShadingIsKept) {
    const int w = 64, h = 32;
    test::Geometry g = test::facingPlane(w, h, 5.0f);
    Image in(size_t(w) * h * 4);
    const float tilt = 12.0f * 3.14159265f / 180.0f;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = (size_t(y) * w + x) * 4;
            const bool lit = (x / 2) % 2 == 0;
            const float nz = g.normal[i + 2];  // the facing normal is (0, 0, +-1)
            g.normal[i + 0] = (lit ? 1.0f : -1.0f) * std::sin(tilt);
            g.normal[i + 2] = nz * std::cos(tilt);
            in[i] = in[i + 1] = in[i + 2] = lit ? 0.9f : 0.3f;
            in[i + 3] = 0.0f;  // N = 0: every pixel is rebuilt
        }
    const std::string old = R"({ "normalAngle": 30, "clampToNeighbours": false })";
    FixRig before(ctx(), w, h, old, false, false, true);
    before.setNormal(g.normal);
    const double errBefore = rmseRed(before.run(in, g.depth), in);
    FixRig after(ctx(), w, h, R"({ "clampToNeighbours": false })", false, false, true);
    after.setNormal(g.normal);
    const double errAfter = rmseRed(after.run(in, g.depth), in);
    EXPECT_GT(errBefore, 0.1) << "30 degrees must mix the bands (else the test cannot fail)";
    EXPECT_LT(errAfter, 0.01);
}

// Issue 13: a clean, smooth first frame (a sine of period 16 px on one plane, no noise) must not
// be flattened by the 16-px level: clampToNeighbours keeps the rebuild inside the pixel's 3x3
// range, which halves the error at least; on noise (DisoccludedFirstFrameErrorIsLower) the range
// is wide and the rebuild still lowers the error.
TEST_F(HistoryFixTest, NeighbourClampKeepsCleanDetail) {
    const int w = 64, h = 32;
    test::Geometry g = test::facingPlane(w, h, 5.0f);
    Image in(size_t(w) * h * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = (size_t(y) * w + x) * 4;
            const float v = 0.5f + 0.3f * std::sin(2.0f * 3.14159265f * float(x) / 16.0f);
            in[i] = in[i + 1] = in[i + 2] = v;
            in[i + 3] = 0.0f;
        }
    FixRig open(ctx(), w, h, R"({ "clampToNeighbours": false })");
    const double errOpen = rmseRed(open.run(in, g.depth), in);
    FixRig clamped(ctx(), w, h, "{}");
    const double errClamped = rmseRed(clamped.run(in, g.depth), in);
    EXPECT_GT(errOpen, 0.1) << "the 16-px level must flatten the sine (else the test cannot fail)";
    EXPECT_LT(errClamped, 0.5 * errOpen);
}

// historyFixFrames = 0 uses the copy-only pipeline: every pixel, N = 0 included, is bit-exact.
TEST_F(HistoryFixTest, ZeroFixFramesIsACopy) {
    const int w = 64, h = 32;
    test::Geometry g = test::facingPlane(w, h, 5.0f);
    const Image in = noisyPlane(w, h, 0.3f, 7u, [](int, int) { return 0.0f; });
    FixRig rig(ctx(), w, h, R"({ "historyFixFrames": 0 })");
    const Image out = rig.run(in, g.depth);
    for (size_t i = 0; i < in.size(); ++i) ASSERT_EQ(out[i], in[i]) << i;
}
