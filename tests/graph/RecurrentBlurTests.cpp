// GPU tests of RecurrentBlur (seed 004, the ReBLUR talk; oracles of specs §2): the talk's proof
// slide (running mean up to N = 30, then an EMA of 1/31), the frame count and its resets (plane
// moved 2 % vs 0.5 % of the frustum size, camera cut), a noise-free constant through every stage
// for 100 frames (no gain in the loop), the blur radius per N against the documented table,
// NaN/Inf never becoming permanent, every output pixel written (sky next to geometry, outputs
// poisoned with NaN first), and no tap crossing the stereo seam.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/scene/Camera.h"
#include "core/util/Error.h"
#include "tests/graph/GpuTestFixture.h"
#include "tests/graph/RecurrentBlurRig.h"

using namespace fovea;
using fovea::test::Image;
using fovea::test::noise;
using fovea::test::ReblurRig;

namespace {

class RecurrentBlurTest : public GpuTest {};

float at(const Image& img, int w, int x, int y, int c) {
    return img[(size_t(y) * w + x) * 4 + c];
}

bool imageAllFinite(const Image& img) {
    return std::all_of(img.begin(), img.end(), [](float v) { return std::isfinite(v); });
}

// Radius 0 everywhere, no pre-blur, no stabilization, no firefly suppressor: the recurrence is
// the bare temporal accumulation (the talk's proof slide).
const char* kBareTemporal =
    R"({ "maxBlurRadius": 0, "minBlurRadius": 0, "prepassBlurRadius": 0, "fireflySuppression": false })";
const char* kBareSpatial =
    R"({ "maxBlurRadius": 0, "minBlurRadius": 0, "maxStabilizedFrames": 0 })";

}  // namespace

// The talk's slide "proof N = 2" generalized: with a = 1/(1+N) the output is the exact running
// mean of all frames while N < 30, then an exponential moving average with weight 1/31.
TEST_F(RecurrentBlurTest, ProofSlideRunningMeanThenEma) {
    const int w = 8, h = 8, frames = 40;
    ReblurRig rig(ctx(), w, h, kBareTemporal, kBareSpatial);
    rig.init();
    rig.setGeometry(test::facingPlane(w, h, 10.0f));
    std::vector<double> mean(size_t(w) * h * 4, 0.0);
    for (int f = 0; f < frames; ++f) {
        const Image in = noise(w, h, 1000 + f);
        rig.frame(in);
        const double n = std::min(f, 30);
        const double a = 1.0 / (1.0 + n);
        for (size_t i = 0; i < mean.size(); ++i)
            mean[i] = f == 0 ? in[i] : mean[i] + a * (in[i] - mean[i]);
        const Image out = rig.get("rbs.result"), acc = rig.get("rbt.accumulated");
        double worst = 0.0;
        for (size_t i = 0; i < out.size(); ++i) {
            if (i % 4 == 3) {
                ASSERT_EQ(acc[i], float(n)) << "frame count, frame " << f;
                continue;
            }
            worst = std::max(worst, std::fabs(double(out[i]) - mean[i]));
        }
        EXPECT_LT(worst, 1e-6) << "frame " << f << " (N = " << n << ")";
    }
}

// N counts 0, 1, 2, ... and stops at 30; a plane that moves towards the camera by 0.5 % of the
// frustum size keeps its history, by 2 % loses it (threshold 1 %); a camera cut resets it.
TEST_F(RecurrentBlurTest, FrameCountProgressionAndResets) {
    const int w = 8, h = 8;
    ReblurRig rig(ctx(), w, h, "{}", "{}");
    rig.init();
    float z = 10.0f;
    rig.setGeometry(test::facingPlane(w, h, z));
    const Image in = test::constantImage(w, h, 0.4f, 0.5f, 0.6f);
    auto count = [&] { return rig.get("rbt.accumulated")[(size_t(4) * w + 4) * 4 + 3]; };
    for (int f = 0; f < 33; ++f) {
        rig.frame(in);
        EXPECT_EQ(count(), float(std::min(f, 30))) << "frame " << f;
    }
    auto moveBy = [&](float fraction) {
        z -= fraction * 2.0f * test::kTanHalfFov * z;  // the plane comes closer
        rig.setGeometry(test::facingPlane(w, h, z));
        rig.frame(in);
    };
    moveBy(0.005f);
    EXPECT_EQ(count(), 30.0f) << "0.5 % of the frustum size keeps the history";
    moveBy(0.02f);
    EXPECT_EQ(count(), 0.0f) << "2 % of the frustum size is a disocclusion";
    rig.frame(in);
    rig.frame(in);
    EXPECT_EQ(count(), 2.0f);
    scene::FrameCamera cut = rig.graph().camera();
    cut.cut = true;
    rig.graph().setCamera(cut);
    rig.frame(in);
    EXPECT_EQ(count(), 0.0f) << "a camera cut resets N";
}

// The normal test of the disocclusion (ours, disocclusionNormal 0.5): the same positions with the
// normal turned by 90 degrees (a floor point in the plane of a box's side face: plane distance 0)
// reset N; a 30-degree turn keeps it; with the test off (-1) the 90-degree turn keeps it too.
TEST_F(RecurrentBlurTest, TurnedNormalOnTheSamePlaneResets) {
    const int w = 8, h = 8;
    const Image in = test::constantImage(w, h, 0.4f, 0.5f, 0.6f);
    auto turned = [&](float degrees) {
        test::Geometry g = test::facingPlane(w, h, 10.0f);
        const float a = degrees * 3.14159265f / 180.0f;
        for (size_t i = 0; i < g.normal.size(); i += 4) {
            g.normal[i] = std::sin(a);
            g.normal[i + 2] = std::cos(a);
        }
        return g;
    };
    for (const char* params : {"{}", R"({ "disocclusionNormal": -1 })"}) {
        ReblurRig rig(ctx(), w, h, params, "{}");
        rig.init();
        auto count = [&] { return rig.get("rbt.accumulated")[(size_t(4) * w + 4) * 4 + 3]; };
        rig.setGeometry(turned(0.0f));
        for (int f = 0; f < 5; ++f) rig.frame(in);
        ASSERT_EQ(count(), 4.0f);
        rig.setGeometry(turned(30.0f));
        rig.frame(in);
        EXPECT_EQ(count(), 5.0f) << params << ": 30 degrees keep the history";
        rig.setGeometry(turned(120.0f));
        rig.frame(in);
        EXPECT_EQ(count(), std::string(params) == "{}" ? 0.0f : 6.0f)
            << params << ": a 90-degree turn at plane distance 0";
    }
}

// A noise-free constant passes every stage unchanged for 100 frames with all stages on
// (pre-blur, firefly suppressor, HistoryFix, blur, post-blur, stabilization): every weighted sum
// is normalized and nothing in the loop has a gain. Half of the pixels have no indirect hit.
TEST_F(RecurrentBlurTest, ConstantPassesEveryStageUnchanged) {
    const int w = 24, h = 16;
    ReblurRig rig(ctx(), w, h, "{}", "{}", true);
    rig.init();
    rig.setGeometry(test::facingPlane(w, h, 5.0f));
    const float c[3] = {0.3f, 0.5f, 0.7f};
    const Image in = test::constantImage(w, h, c[0], c[1], c[2]);
    std::vector<float> hit(size_t(w) * h, 0.0f);
    for (size_t i = 0; i < hit.size(); i += 2) hit[i] = 2.0f;
    for (int f = 1; f <= 100; ++f) {
        rig.frame(in, hit);
        if (f != 1 && f != 3 && f % 25 != 0) continue;
        for (const char* o : {"rbt.preblurred", "rbt.accumulated", "hf.result", "rbs.blurred",
                              "rbs.history", "rbs.result"}) {
            const Image out = rig.get(o);
            float worst = 0.0f;
            for (size_t i = 0; i < out.size(); ++i)
                if (i % 4 != 3) worst = std::max(worst, std::fabs(out[i] - c[i % 4]));
            EXPECT_LT(worst, 2e-6f) << o << " frame " << f;
        }
    }
}

// The blur radius per N (debug output rbs.radius) against the table of
// docs/passes/RecurrentBlur.md (NoV = 1, no indirect hit = h = 1, historyFixFrames 3):
// sqrt: 30, 30, 30, 18.97, 13.42 ... 5.39 at N = 30; linear: 30, 30, 30, 12, 6 ... 1 (the floor).
TEST_F(RecurrentBlurTest, RadiusPerFrameCountMatchesTable) {
    const int w = 8, h = 8;
    struct Row {
        int n;
        float sqrtRadius, linearRadius;
    };
    const Row table[] = {{0, 30.0f, 30.0f},   {1, 30.0f, 30.0f},  {2, 30.0f, 30.0f},
                         {3, 18.974f, 12.0f}, {4, 13.416f, 6.0f}, {10, 9.045f, 2.727f},
                         {30, 5.388f, 1.0f}};
    for (const char* scaling : {"sqrt", "linear"}) {
        ReblurRig rig(ctx(), w, h, "{}", std::string(R"({ "radiusScaling": ")") + scaling + "\" }");
        rig.init();
        rig.setGeometry(test::facingPlane(w, h, 5.0f));
        const Image in = test::constantImage(w, h, 0.5f, 0.5f, 0.5f);
        size_t row = 0;
        for (int f = 0; f <= 30 && row < std::size(table); ++f) {
            rig.frame(in);
            if (f != table[row].n) continue;
            const float want =
                std::string(scaling) == "sqrt" ? table[row].sqrtRadius : table[row].linearRadius;
            const Image r = rig.get("rbs.radius");
            EXPECT_NEAR(r[(size_t(4) * w + 4) * 4], want, 0.01f) << scaling << " N = " << f;
            ++row;
        }
        EXPECT_EQ(row, std::size(table));
    }
}

// Resolution scale (issue 13): maxBlurRadius is pixels at referenceHeight rows. On 8 rows with
// referenceHeight 16 the table halves: 15 px at N = 0, 2.694 at N = 30 (sqrt); minBlurRadius
// (1 px) is not scaled.
TEST_F(RecurrentBlurTest, RadiusScalesWithReferenceHeight) {
    const int w = 8, h = 8;
    ReblurRig rig(ctx(), w, h, "{}", R"({ "referenceHeight": 16 })");
    rig.init();
    rig.setGeometry(test::facingPlane(w, h, 5.0f));
    const Image in = test::constantImage(w, h, 0.5f, 0.5f, 0.5f);
    for (int f = 0; f <= 30; ++f) {
        rig.frame(in);
        const float r = rig.get("rbs.radius")[(size_t(4) * w + 4) * 4];
        if (f == 0) {
            EXPECT_NEAR(r, 15.0f, 0.01f);
        }
        if (f == 30) {
            EXPECT_NEAR(r, 2.694f, 0.01f);
        }
    }
}

// Both signals (issue 26: RecurrentBlur{signal: specular} with roughness fed) for the robustness
// tests below: NaN/Inf and the stereo seam.
class RecurrentBlurBothSignals : public GpuTest, public ::testing::WithParamInterface<const char*> {
protected:
    // {"signal": <param>, extra...}
    static std::string withSignal(const std::string& extra = "") {
        return std::string(R"({ "signal": ")") + GetParam() + "\"" + extra + " }";
    }
    static bool specular() { return std::string(GetParam()) == "specular"; }
};
INSTANTIATE_TEST_SUITE_P(Signal, RecurrentBlurBothSignals,
                         ::testing::Values("diffuse", "specular"));

// NaN/Inf radiance, a NaN/Inf hit distance, a NaN normal and an infinite position on one frame:
// every output of every stage stays finite in that frame and all later ones, and the image
// returns to the clean value (the feedback loop would otherwise keep a NaN forever).
TEST_P(RecurrentBlurBothSignals, NaNAndInfNeverBecomePermanent) {
    const int w = 16, h = 16;
    ReblurRig rig(ctx(), w, h, withSignal(), withSignal(), true);
    rig.init();
    if (specular()) rig.setRoughness(0.5f);
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
    for (const char* o : outputs) EXPECT_TRUE(imageAllFinite(rig.get(o))) << o << " (bad frame)";
    for (int f = 0; f < 40; ++f) rig.frame(in);
    for (const char* o : outputs)
        EXPECT_TRUE(imageAllFinite(rig.get(o))) << o << " (40 frames later)";
    const Image out = rig.get("rbs.result");
    for (size_t i = 0; i < out.size(); ++i)
        if (i % 4 != 3) {
            ASSERT_NEAR(out[i], in[i], 0.05f) << "float " << i;
        }
}

// Sky (depth 0) next to geometry, every output first filled with NaN: after one frame every
// pixel of every output is finite, so every kernel wrote every pixel (NRD #88: sky early-outs).
TEST_F(RecurrentBlurTest, EveryKernelWritesEveryPixel) {
    const int w = 16, h = 16;
    std::vector<float> depth(size_t(w) * h, 4.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w / 2; ++x) depth[size_t(y) * w + x] = 0.0f;  // left half: sky
    ReblurRig rig(ctx(), w, h, "{}", "{}", true);
    rig.init();
    rig.setGeometry(test::facingPlanes(w, h, depth));
    const char* outputs[] = {"rbt.preblurred", "rbt.accumulated", "rbt.hit",
                             "rbt.radius",     "hf.result",       "rbs.blurred",
                             "rbs.history",    "rbs.result",      "rbs.radius"};
    for (const char* o : outputs) rig.poison(o, std::numeric_limits<float>::quiet_NaN());
    rig.frame(noise(w, h, 5));
    for (const char* o : outputs) EXPECT_TRUE(imageAllFinite(rig.get(o))) << o;
}

// Two eyes side by side: the left eye sees 0, the right eye 1 on one continuous plane. With the
// full blur (radius 30, much wider than an eye; specular: roughness 1, the widest world-space
// kernel) and a sideways motion that would fetch history from the other eye, no value crosses
// the seam: the left eye stays exactly 0.
TEST_P(RecurrentBlurBothSignals, TapsNeverCrossTheStereoSeam) {
    const int w = 32, h = 16;
    const std::string eyes = withSignal(R"(, "eyes": 2)");
    ReblurRig rig(ctx(), w, h, eyes, eyes, true, R"({ "eyes": 2 })");
    rig.init();
    if (specular()) rig.setRoughness(1.0f);
    rig.setGeometry(test::facingPlane(w, h, 5.0f));
    Image in = test::constantImage(w, h, 0.0f, 0.0f, 0.0f);
    for (int y = 0; y < h; ++y)
        for (int x = w / 2; x < w; ++x)
            for (int k = 0; k < 3; ++k) in[(size_t(y) * w + x) * 4 + k] = 1.0f;
    Image motion(size_t(w) * h * 4, 0.0f);
    for (size_t i = 0; i < motion.size(); i += 4) motion[i] = 3.0f;  // history 3 px to the right
    for (int f = 0; f < 5; ++f) {
        if (f == 2) rig.setMotion(motion);
        rig.frame(in);
        for (const char* o : {"rbt.preblurred", "rbt.accumulated", "hf.result", "rbs.blurred",
                              "rbs.history", "rbs.result"}) {
            const Image out = rig.get(o);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w / 2; ++x)
                    for (int k = 0; k < 3; ++k)
                        ASSERT_EQ(at(out, w, x, y, k), 0.0f) << o << " " << x << "," << y;
        }
    }
}

// The lag-vs-blur trade-off of seed 004 as a measured curve: a static lit plane (0.1, +-50 %
// noise) switches to 1.0 (same relative noise) after N reached 30; frames until the image mean
// of the output reaches 90 % of the step. The accumulation alone needs ceil(ln 0.1 / ln(30/31))
// = 71 frames (specs §2; noise moves the crossing by a frame or two); the luminance
// stabilization (which only acts inside the neighbourhood's sigma band) may add lag, its antilag
// removes it again. The curves are printed for docs/benchmarks.md.
TEST_F(RecurrentBlurTest, LightSwitchLag) {
    const int w = 16, h = 16;
    struct Config {
        const char* label;
        std::string temporal, spatial;
    };
    const Config configs[] = {
        {"accumulation only (radius 0, no stabilization)", kBareTemporal, kBareSpatial},
        {"+ stabilization, antilag off", kBareTemporal,
         R"({ "maxBlurRadius": 0, "minBlurRadius": 0, "antilag": false })"},
        {"+ stabilization + antilag", kBareTemporal,
         R"({ "maxBlurRadius": 0, "minBlurRadius": 0 })"},
        {"all defaults (blur, firefly suppressor, stabilization, antilag)", "{}", "{}"},
    };
    auto lit = [&](float level, uint32_t seed) {
        Image img = noise(w, h, seed);
        for (size_t i = 0; i < img.size(); ++i)
            if (i % 4 != 3) img[i] = level * (0.5f + img[i]);
        return img;
    };
    int lag[4] = {0, 0, 0, 0};
    for (int c = 0; c < 4; ++c) {
        ReblurRig rig(ctx(), w, h, configs[c].temporal, configs[c].spatial);
        rig.init();
        rig.setGeometry(test::facingPlane(w, h, 5.0f));
        for (int f = 0; f < 40; ++f) rig.frame(lit(0.1f, 7000 + f));
        std::string curve;
        for (int k = 1; k <= 400 && lag[c] == 0; ++k) {
            rig.frame(lit(1.0f, 9000 + k));
            const Image out = rig.get("rbs.result");
            double mean = 0.0;
            for (size_t i = 0; i < out.size(); i += 4) mean += out[i];
            mean /= double(w * h);
            if (k <= 5 || k % 10 == 0)
                curve += " " + std::to_string(k) + ":" + std::to_string(mean);
            if (mean >= 0.1 + 0.9 * 0.9) lag[c] = k;
        }
        std::printf("[light switch] %s: 90 %% after %d frames; mean by frame:%s\n",
                    configs[c].label, lag[c], curve.c_str());
    }
    EXPECT_GE(lag[0], 69);
    EXPECT_LE(lag[0], 73);
    EXPECT_GE(lag[1], lag[0]) << "stabilization without antilag adds no speed";
    EXPECT_LE(lag[2], lag[1]) << "antilag never slows it down";
    EXPECT_GT(lag[3], 0) << "the defaults reach 90 % within 400 frames";
}

// A temporal stage without its recurrent input is rejected at compile (exit 2 in the CLI) with the
// pass's pointer (`history` is a required input), not run as an accumulation that never has
// history.
TEST_F(RecurrentBlurTest, TemporalStageWithoutHistoryEdgeIsAnInputError) {
    const std::string text = R"({ "version": 1, "name": "x", "passes": [
        { "name": "feed", "type": "Feed" },
        { "name": "rbt", "type": "RecurrentBlurTemporal" } ], "edges": [
        { "from": "feed.radiance", "to": "rbt.radiance" },
        { "from": "feed.hit_distance", "to": "rbt.hit_distance" },
        { "from": "feed.normal", "to": "rbt.normal" },
        { "from": "feed.position", "to": "rbt.position" },
        { "from": "feed.depth", "to": "rbt.depth" } ], "outputs": [ "rbt.accumulated" ] })";
    graph::RenderGraph g(ctx(), test::reblurRegistry());
    graph::CompileOptions o;
    o.width = o.height = 8;
    try {
        g.build(graph::parseGraphText(text, "x.json"), o);
        FAIL() << "no error";
    } catch (const InputError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("/passes/1"), std::string::npos) << what;
        EXPECT_NE(what.find("'rbt.history' has no edge"), std::string::npos) << what;
    }
}

// N is the bilinear-weighted average of the valid taps' counts plus one, never their max: the
// right half of a plane appears at frame 10 (N = 0 there, N = 10 on the left); with a motion of
// +0.5 px the next frame's pixel x = 3 reads taps x = 3 (N = 10) and x = 4 (N = 0) at 1/2 each:
// N = 6 (a max would give 11).
TEST_F(RecurrentBlurTest, FrameCountIsTheWeightedTapAverage) {
    const int w = 8, h = 4;
    ReblurRig rig(ctx(), w, h, "{}", "{}");
    rig.init();
    std::vector<float> halfSky(size_t(w) * h, 5.0f);
    for (int y = 0; y < h; ++y)
        for (int x = w / 2; x < w; ++x) halfSky[size_t(y) * w + x] = 0.0f;
    rig.setGeometry(test::facingPlanes(w, h, halfSky));
    const Image in = test::constantImage(w, h, 0.5f, 0.5f, 0.5f);
    for (int f = 0; f < 10; ++f) rig.frame(in);
    rig.setGeometry(test::facingPlane(w, h, 5.0f));
    rig.frame(in);
    Image acc = rig.get("rbt.accumulated");
    EXPECT_EQ(at(acc, w, 3, 1, 3), 10.0f);
    EXPECT_EQ(at(acc, w, 4, 1, 3), 0.0f);
    Image motion(size_t(w) * h * 4, 0.0f);
    for (size_t i = 0; i < motion.size(); i += 4) motion[i] = 0.5f;
    rig.setMotion(motion);
    rig.frame(in);
    acc = rig.get("rbt.accumulated");
    EXPECT_FLOAT_EQ(at(acc, w, 3, 1, 3), 6.0f);
    EXPECT_FLOAT_EQ(at(acc, w, 5, 1, 3), 1.0f);
}
