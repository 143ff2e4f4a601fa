// GPU tests of the TAA pass (Karis 2014; seed 003 P2 §3): exponential blend semantics of `alpha`,
// convergence under a still camera, exact reprojection of a moving pattern (integer motion: the
// output equals the input; fractional motion, bilinear and Catmull-Rom: equals a CPU reference
// of the shader), ghost removal by the min/max and variance clips, reset on camera cut and on
// an invalid history, NaN/Inf never reaching the history, and no read across the stereo seam.
// Inputs come from a no-op "Feed" pass whose persistent outputs the test uploads every frame;
// TAA's history is its own previous `result`, kept by the graph (pass-declared history).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/scene/BuiltinScenes.h"
#include "core/scene/Camera.h"
#include "core/scene/SceneGpu.h"
#include "core/vk/Resources.h"
#include "passes/RegisterPasses.h"
#include "passes/TAA/TAAPass.h"
#include "tests/passes/FeedPass.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::graph;

namespace {

const PassRegistry& registry() {
    // Motion in GBuffer's format.
    static PassRegistry r = test::feedRegistry<passes::TAAPass>(
        "TAA", {{"color", vk::Format::eR32G32B32A32Sfloat}, {"motion", vk::Format::eR16G16Sfloat}});
    return r;
}

using Image = std::vector<float>;  // rgba32f, row-major

// --- CPU reference of shaders/taa/taa.comp (one frame) -----------------------------------------

struct RefParams {
    float alpha = 0.1f;
    int clip = 2;  // 0 none, 1 minmax, 2 variance
    float gamma = 1.0f;
    bool catmullRom = false;
    int eyes = 1;
};

struct V3 {
    double v[3] = {0, 0, 0};
};

V3 toYCoCg(const float* c) {
    return {{0.25 * c[0] + 0.5 * c[1] + 0.25 * c[2], 0.5 * c[0] - 0.5 * c[2],
             -0.25 * c[0] + 0.5 * c[1] - 0.25 * c[2]}};
}
V3 fromYCoCg(const V3& c) {
    return {{c.v[0] + c.v[1] - c.v[2], c.v[0] + c.v[2], c.v[0] - c.v[1] - c.v[2]}};
}

V3 clipToBox(const V3& h, const V3& centre, const V3& extent) {
    double s = 1.0;
    for (int k = 0; k < 3; ++k) {
        double a = std::fabs(h.v[k] - centre.v[k]);
        if (a > extent.v[k]) s = std::min(s, extent.v[k] / a);
    }
    V3 r;
    for (int k = 0; k < 3; ++k) r.v[k] = centre.v[k] + (h.v[k] - centre.v[k]) * s;
    return r;
}

double catmullRom(double t, int k) {
    double t2 = t * t, t3 = t2 * t;
    switch (k) {
        case 0:
            return -0.5 * t3 + t2 - 0.5 * t;
        case 1:
            return 1.5 * t3 - 2.5 * t2 + 1.0;
        case 2:
            return -1.5 * t3 + 2.0 * t2 + 0.5 * t;
        default:
            return 0.5 * t3 - 0.5 * t2;
    }
}

// `history` null = invalid (first frame / reset). Inputs must be finite.
Image taaReference(int w, int h, const Image& color, const Image& motion, const Image* history,
                   const RefParams& p) {
    Image out(size_t(w) * h * 4);
    const int eyeWidth = std::max(w / p.eyes, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const int eye = std::min(x / eyeWidth, p.eyes - 1);
            const int x0 = eye * eyeWidth, x1 = eye == p.eyes - 1 ? w - 1 : x0 + eyeWidth - 1;
            auto at = [&](const Image& img, int qx, int qy) {
                qx = std::clamp(qx, x0, x1);
                qy = std::clamp(qy, 0, h - 1);
                return &img[(size_t(qy) * w + qx) * 4];
            };
            const float* c = at(color, x, y);
            V3 mn{{1e300, 1e300, 1e300}}, mx{{-1e300, -1e300, -1e300}}, m1, m2;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    V3 s = toYCoCg(at(color, x + dx, y + dy));
                    for (int k = 0; k < 3; ++k) {
                        mn.v[k] = std::min(mn.v[k], s.v[k]);
                        mx.v[k] = std::max(mx.v[k], s.v[k]);
                        m1.v[k] += s.v[k];
                        m2.v[k] += s.v[k] * s.v[k];
                    }
                }
            const float* mv = at(motion, x, y);
            const double hx = x + 0.5 + mv[0], hy = y + 0.5 + mv[1];
            const bool onScreen = hx >= x0 && hx < x1 + 1 && hy >= 0 && hy < h;
            float* o = &out[(size_t(y) * w + x) * 4];
            for (int k = 0; k < 4; ++k) o[k] = c[k];
            if (!history || !onScreen) continue;
            const double fx = hx - 0.5, fy = hy - 0.5;
            const int ix = int(std::floor(fx)), iy = int(std::floor(fy));
            const double tx = fx - ix, ty = fy - iy;
            double hc[3] = {0, 0, 0};
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) {
                    double wgt;
                    if (p.catmullRom)
                        wgt = catmullRom(tx, i) * catmullRom(ty, j);
                    else if (i >= 1 && i <= 2 && j >= 1 && j <= 2)
                        wgt = (i == 1 ? 1 - tx : tx) * (j == 1 ? 1 - ty : ty);
                    else
                        continue;
                    const float* s = at(*history, ix + i - 1, iy + j - 1);
                    for (int k = 0; k < 3; ++k) hc[k] += wgt * s[k];
                }
            float hf[3] = {float(hc[0]), float(hc[1]), float(hc[2])};
            V3 hyc = toYCoCg(hf);
            if (p.clip == 1) {
                V3 centre, extent;
                for (int k = 0; k < 3; ++k) {
                    centre.v[k] = 0.5 * (mn.v[k] + mx.v[k]);
                    extent.v[k] = 0.5 * (mx.v[k] - mn.v[k]);
                }
                hyc = clipToBox(hyc, centre, extent);
            } else if (p.clip == 2) {
                V3 mu, extent;
                for (int k = 0; k < 3; ++k) {
                    mu.v[k] = m1.v[k] / 9.0;
                    extent.v[k] =
                        p.gamma * std::sqrt(std::max(m2.v[k] / 9.0 - mu.v[k] * mu.v[k], 0.0));
                }
                hyc = clipToBox(hyc, mu, extent);
            }
            V3 hr = fromYCoCg(hyc);
            for (int k = 0; k < 3; ++k) o[k] = float(hr.v[k] + (c[k] - hr.v[k]) * p.alpha);
        }
    return out;
}

// --- helpers -----------------------------------------------------------------------------------

Image constant(int w, int h, float r, float g, float b) {
    Image img(size_t(w) * h * 4);
    for (size_t i = 0; i < img.size(); i += 4) {
        img[i] = r;
        img[i + 1] = g;
        img[i + 2] = b;
        img[i + 3] = 1.0f;
    }
    return img;
}

Image noise(int w, int h, uint32_t seed, float lo = 0.0f, float hi = 1.0f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(lo, hi);
    Image img(size_t(w) * h * 4);
    for (size_t i = 0; i < img.size(); ++i) img[i] = (i % 4 == 3) ? 1.0f : u(rng);
    return img;
}

Image uniformMotion(int w, int h, float mx, float my) {
    Image img(size_t(w) * h * 4, 0.0f);
    for (size_t i = 0; i < img.size(); i += 4) {
        img[i] = mx;
        img[i + 1] = my;
    }
    return img;
}

// A smooth-ish periodic pattern T(x, y) sampled at integer pixel centres shifted by (sx, sy).
Image pattern(int w, int h, int sx, int sy) {
    Image img(size_t(w) * h * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            int u = x - sx, v = y - sy;
            float* o = &img[(size_t(y) * w + x) * 4];
            o[0] = 0.5f + 0.5f * std::sin(0.7f * u + 0.3f * v);
            o[1] = float(((u % 5) + 5) % 5) / 4.0f;
            o[2] = float(((v % 3) + 3) % 3) / 2.0f;
            o[3] = 1.0f;
        }
    return img;
}

::testing::AssertionResult near(const Image& got, const Image& want, float tol,
                                bool rgbOnly = true) {
    if (got.size() != want.size())
        return ::testing::AssertionFailure() << got.size() << " vs " << want.size() << " floats";
    size_t bad = 0, first = 0;
    for (size_t i = 0; i < got.size(); ++i) {
        if (rgbOnly && i % 4 == 3) continue;
        if (!(std::fabs(got[i] - want[i]) <= tol) && bad++ == 0) first = i;
    }
    if (bad == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << bad << " values differ; first: pixel " << first / 4 << " channel " << first % 4
           << ": " << got[first] << " vs " << want[first];
}

bool allFinite(const Image& img) {
    return std::all_of(img.begin(), img.end(), [](float v) { return std::isfinite(v); });
}

// Feed -> TAA (the graph keeps TAA's previous result as its history). One instance per test.
class TaaRig {
public:
    TaaRig(gpu::Context& gpu, int w, int h, const std::string& params, bool useMotion = true)
        : mGpu(gpu), mGraph(gpu, registry()), mW(w), mH(h), mUseMotion(useMotion) {
        std::string edges = R"({ "from": "feed.color", "to": "taa.color" })";
        if (useMotion) edges += R"(, { "from": "feed.motion", "to": "taa.motion" })";
        const std::string text =
            R"({ "version": 1, "name": "taa_test", "passes": [ { "name": "feed", "type": )"
            R"("Feed" }, { "name": "taa", "type": "TAA", "params": )" +
            params + R"( } ], "edges": [ )" + edges + R"( ], "outputs": [ "taa.result" ] })";
        CompileOptions o;
        o.width = uint32_t(w);
        o.height = uint32_t(h);
        mGraph.build(parseGraphText(text, "taa_test"), o);
    }

    // Uploads the inputs, runs one frame, returns taa.result. `motionUsed` receives the motion
    // as the shader reads it (rounded to fp16).
    Image frame(const Image& color, const Image& motion, Image* motionUsed = nullptr) {
        target("feed.color").uploadRGBA32F(mGpu, color);
        if (mUseMotion) target("feed.motion").uploadRGBA32F(mGpu, motion);
        if (motionUsed && mUseMotion)
            *motionUsed = mGraph.image("feed.motion").downloadRGBA32F(mGpu);
        mGraph.runFrame();
        return mGraph.image("taa.result").downloadRGBA32F(mGpu);
    }
    Image frame(const Image& color) { return frame(color, uniformMotion(mW, mH, 0, 0)); }
    RenderGraph& graph() { return mGraph; }

private:
    // Feed never writes its outputs; the test fills them from the host before each frame.
    gpu::Image& target(const char* name) { return const_cast<gpu::Image&>(mGraph.image(name)); }
    gpu::Context& mGpu;
    RenderGraph mGraph;
    int mW, mH;
    bool mUseMotion;
};

class TAATest : public GpuTest {};

}  // namespace

// alpha is the weight of the current frame: 1 = the current frame exactly, 0 = the first frame
// forever (clip off), 0.25 = mix(history, current, 0.25) exactly.
TEST_F(TAATest, AlphaIsTheCurrentFrameWeight) {
    const int w = 16, h = 16;
    std::vector<Image> frames;
    for (uint32_t s = 0; s < 3; ++s) frames.push_back(noise(w, h, 100 + s));
    for (float alpha : {1.0f, 0.0f, 0.25f}) {
        TaaRig rig(ctx(), w, h, R"({ "alpha": )" + std::to_string(alpha) + R"(, "clip": "none" })");
        Image previous;
        for (size_t f = 0; f < frames.size(); ++f) {
            Image got = rig.frame(frames[f]);
            Image want(got.size());
            for (size_t i = 0; i < want.size(); ++i)
                want[i] = f == 0 || i % 4 == 3 ? frames[f][i]
                                               : previous[i] + alpha * (frames[f][i] - previous[i]);
            EXPECT_TRUE(near(got, want, 1e-5f)) << "alpha " << alpha << " frame " << f;
            previous = got;
        }
    }
}

// Still camera, constant input after a different first frame: the error to the input decays as
// (1 - alpha)^n (clip off, so only the blend acts) and the output converges to the input.
TEST_F(TAATest, StaticConstantInputConverges) {
    const int w = 16, h = 16;
    const float alpha = 0.3f;
    TaaRig rig(ctx(), w, h, R"({ "alpha": 0.3, "clip": "none" })");
    const Image start = noise(w, h, 7), target = constant(w, h, 0.2f, 0.6f, 0.9f);
    rig.frame(start);
    Image got;
    const int n = 12;
    for (int f = 1; f <= n; ++f) got = rig.frame(target);
    const double decay = std::pow(1.0 - alpha, n);
    Image want(got.size());
    for (size_t i = 0; i < want.size(); ++i)
        want[i] = i % 4 == 3 ? 1.0f : float(target[i] + decay * (start[i] - target[i]));
    EXPECT_TRUE(near(got, want, 1e-4f));
    EXPECT_TRUE(near(got, target, 0.02f));  // (0.7)^12 ~ 0.014 of at most 1
    // With the default (variance clip) a constant input is reached in one frame.
    TaaRig clipped(ctx(), w, h, "{}");
    clipped.frame(start);
    EXPECT_TRUE(near(clipped.frame(target), target, 1e-6f));
}

// A pattern moving by an integer number of pixels per frame with exact motion vectors (previous
// pixel - current pixel = -velocity): perfect reprojection makes the history equal the current
// frame wherever it exists, so the output equals the input exactly even without any clip.
// A wrong sign, a missing half-pixel or an off-by-one in the fetch breaks this.
TEST_F(TAATest, MovingPatternIntegerMotionIsExact) {
    const int w = 32, h = 24;
    TaaRig rig(ctx(), w, h, R"({ "alpha": 0.2, "clip": "none" })");
    const int vx = 2, vy = -1;
    for (int f = 0; f < 4; ++f) {
        Image in = pattern(w, h, vx * f, vy * f);
        Image got = rig.frame(in, uniformMotion(w, h, -float(vx), -float(vy)));
        EXPECT_TRUE(near(got, in, 1e-5f)) << "frame " << f;
    }
    // Control: the same frames without motion blend stale history and differ.
    TaaRig still(ctx(), w, h, R"({ "alpha": 0.2, "clip": "none" })", false);
    still.frame(pattern(w, h, 0, 0));
    EXPECT_FALSE(near(still.frame(pattern(w, h, vx, vy)), pattern(w, h, vx, vy), 1e-3f));
}

// Fractional motion: bilinear and Catmull-Rom history with each clip mode equal the CPU
// reference of the shader, frame after frame (the reference takes the GPU's previous result as
// history, so each frame is checked on its own).
TEST_F(TAATest, MovingPatternFractionalMotionMatchesReference) {
    const int w = 32, h = 24;
    struct Case {
        const char* params;
        RefParams ref;
    };
    const Case cases[] = {
        {R"({ "alpha": 0.25, "clip": "none" })", {0.25f, 0, 1.0f, false, 1}},
        {R"({ "alpha": 0.25, "clip": "none", "historyFilter": "catmull-rom" })",
         {0.25f, 0, 1.0f, true, 1}},
        {R"({ "alpha": 0.1, "clip": "minmax" })", {0.1f, 1, 1.0f, false, 1}},
        {R"({ "alpha": 0.1, "clip": "variance", "gamma": 1.25, "historyFilter": "catmull-rom" })",
         {0.1f, 2, 1.25f, true, 1}},
    };
    for (const Case& c : cases) {
        TaaRig rig(ctx(), w, h, c.params);
        Image previous;
        for (int f = 0; f < 3; ++f) {
            Image in = noise(w, h, 40 + f);
            Image motion = uniformMotion(w, h, 1.25f, -0.75f), used;
            Image got = rig.frame(in, motion, &used);
            Image want = taaReference(w, h, in, used, f == 0 ? nullptr : &previous, c.ref);
            EXPECT_TRUE(near(got, want, 2e-5f)) << c.params << " frame " << f;
            previous = got;
        }
    }
}

// A bright object leaves: its history is far outside the new neighbourhood. The min/max clip
// removes it completely on a flat background; the variance clip brings it inside mean +-
// gamma*sigma (checked against the reference); without a clip the ghost stays.
TEST_F(TAATest, ClipRemovesGhost) {
    const int w = 24, h = 24;
    Image ghost = constant(w, h, 0.3f, 0.3f, 0.3f);
    for (int y = 8; y < 16; ++y)
        for (int x = 8; x < 16; ++x)
            for (int k = 0; k < 3; ++k) ghost[(size_t(y) * w + x) * 4 + k] = 20.0f;
    const Image background = constant(w, h, 0.3f, 0.3f, 0.3f);
    {
        TaaRig rig(ctx(), w, h, R"({ "clip": "minmax" })");
        rig.frame(ghost);
        EXPECT_TRUE(near(rig.frame(background), background, 1e-6f));
    }
    {
        TaaRig rig(ctx(), w, h, R"({ "clip": "none" })");
        rig.frame(ghost);
        Image got = rig.frame(background);
        EXPECT_NEAR(got[(size_t(12) * w + 12) * 4], 0.9f * 20.0f + 0.1f * 0.3f, 1e-4f);
    }
    {
        const Image noisy = noise(w, h, 9, 0.2f, 0.4f);
        TaaRig rig(ctx(), w, h, R"({ "clip": "variance", "gamma": 1.0 })");
        Image first = rig.frame(ghost), used;
        Image got = rig.frame(noisy, uniformMotion(w, h, 0, 0), &used);
        EXPECT_TRUE(
            near(got, taaReference(w, h, noisy, used, &first, {0.1f, 2, 1.0f, false, 1}), 2e-5f));
        for (size_t i = 0; i < got.size(); ++i)
            if (i % 4 != 3) {
                EXPECT_LT(got[i], 0.6f) << "ghost left at float " << i;
            }
    }
}

// The first frame, a reset and a camera cut (setCamera with cut) all restart from the current
// frame alone, even with alpha small and the clip off.
TEST_F(TAATest, CameraCutAndInvalidHistoryReset) {
    const int w = 16, h = 16;
    TaaRig rig(ctx(), w, h, R"({ "alpha": 0.05, "clip": "none" })");
    const Image a = noise(w, h, 1), b = noise(w, h, 2), c = noise(w, h, 3);
    EXPECT_TRUE(near(rig.frame(a), a, 0.0f)) << "first frame (no history)";
    EXPECT_FALSE(near(rig.frame(b), b, 1e-3f)) << "history in use";
    rig.graph().reset();
    EXPECT_TRUE(near(rig.frame(c), c, 0.0f)) << "after reset";
    EXPECT_FALSE(near(rig.frame(a), a, 1e-3f)) << "history in use again";
    scene::FrameCamera cut = rig.graph().camera();
    cut.cut = true;
    rig.graph().setCamera(cut);
    EXPECT_TRUE(near(rig.frame(b), b, 0.0f)) << "after a camera cut";
    EXPECT_FALSE(near(rig.frame(c), c, 1e-3f)) << "the cut lasts one frame";
}

// NaN, Inf and overflowing values in the colour (and NaN motion) never reach the result, which is
// the next frame's history: every frame stays finite, and bad pixels fall back to 0 / the current
// frame.
TEST_F(TAATest, NaNNeverEntersHistory) {
    const int w = 16, h = 16;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    struct Case {
        const char* params;
        RefParams ref;
    };
    const Case cases[] = {
        {R"({ "clip": "variance" })", {0.1f, 2, 1.0f, false, 1}},
        {R"({ "clip": "none" })", {0.1f, 0, 1.0f, false, 1}},
        {R"({ "clip": "minmax", "historyFilter": "catmull-rom" })", {0.1f, 1, 1.0f, true, 1}}};
    for (const Case& c : cases) {
        TaaRig rig(ctx(), w, h, c.params);
        Image bad = noise(w, h, 5);
        bad[(size_t(3) * w + 3) * 4 + 0] = nan;
        bad[(size_t(8) * w + 9) * 4 + 1] = inf;
        bad[(size_t(12) * w + 2) * 4 + 2] = -inf;
        bad[(size_t(5) * w + 5) * 4 + 3] = nan;
        // Finite but extreme: sums and squares of the neighbourhood overflow to Inf (the final
        // sanitize must catch what the input sanitize cannot).
        for (int x = 10; x < 13; ++x)
            for (int k = 0; k < 3; ++k) bad[(size_t(10) * w + x) * 4 + k] = 3.0e38f;
        Image motion = uniformMotion(w, h, 0.5f, 0.25f), used;
        motion[(size_t(7) * w + 7) * 4] = nan;
        Image first = rig.frame(bad, motion);
        EXPECT_TRUE(allFinite(first)) << c.params << " frame 0";
        Image second = rig.frame(bad, motion, &used);
        EXPECT_TRUE(allFinite(second)) << c.params << " frame 1 (bad history?)";
        // Rows 0-6 (NaN colour at (3,3), NaN alpha at (5,5)) behave as if the bad values were
        // 0: a NaN neighbour does not poison the whole 3x3 box (the input sanitize).
        Image clean = bad;
        for (float& v : clean)
            if (!std::isfinite(v)) v = 0.0f;
        Image want = taaReference(w, h, clean, used, &first, c.ref);
        const size_t rows = size_t(7) * w * 4;
        EXPECT_TRUE(near(Image(second.begin(), second.begin() + rows),
                         Image(want.begin(), want.begin() + rows), 2e-5f, false))
            << c.params;
        for (int f = 0; f < 2; ++f) {
            Image got = rig.frame(noise(w, h, 20 + f), motion);
            EXPECT_TRUE(allFinite(got)) << c.params << " later frame " << f;
        }
    }
}

// Stereo 32x16 (two 16-wide eyes), left eye and right eye different colours. Motion +3.25 px:
// left pixel 12 reprojects to 15.75 (its bilinear footprint touches column 16 of the right eye),
// 13..15 land in the right eye (off-screen for the left eye). Neither may read the right eye.
TEST_F(TAATest, StereoSeamIsNotCrossed) {
    const int w = 32, h = 16;
    auto halves = [&](float left, float right) {
        Image img(size_t(w) * h * 4);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int k = 0; k < 4; ++k)
                    img[(size_t(y) * w + x) * 4 + k] = k == 3 ? 1.0f : (x < 16 ? left : right);
        return img;
    };
    const Image motion = uniformMotion(w, h, 3.25f, 0.0f);
    auto runTwo = [&](int eyes) {
        TaaRig rig(ctx(), w, h,
                   R"({ "alpha": 0.5, "clip": "none", "eyes": )" + std::to_string(eyes) + "}");
        rig.frame(halves(1.0f, 9.0f), motion);
        return rig.frame(halves(2.0f, 9.0f), motion);
    };
    Image stereo = runTwo(2);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < 16; ++x) {
            // History exists (x <= 12, within the left eye): mix(1, 2, 0.5); else current (2).
            const float want = x <= 12 ? 1.5f : 2.0f;
            EXPECT_FLOAT_EQ(stereo[(size_t(y) * w + x) * 4], want) << "x " << x << " y " << y;
        }
    Image used = uniformMotion(w, h, 3.25f, 0.0f);
    {
        // The same through the reference (right eye included).
        TaaRig rig(ctx(), w, h, R"({ "alpha": 0.5, "clip": "none", "eyes": 2 })");
        Image first = rig.frame(halves(1.0f, 9.0f), motion);
        Image got = rig.frame(halves(2.0f, 9.0f), motion);
        EXPECT_TRUE(near(
            got, taaReference(w, h, halves(2.0f, 9.0f), used, &first, {0.5f, 0, 1.0f, false, 2}),
            1e-5f));
    }
    // Control: as one eye, the same pixels do read the right half (so the test can fail).
    Image mono = runTwo(1);
    EXPECT_GT(mono[(size_t(4) * w + 12) * 4], 2.0f);

    // Neighbourhood: a left-eye ghost equal to the right eye's colour must still be clipped
    // away at the seam (the box of column 15 may not include column 16).
    TaaRig rig(ctx(), w, h, R"({ "clip": "minmax", "eyes": 2 })", false);
    rig.frame(halves(9.0f, 9.0f));
    Image got = rig.frame(halves(2.0f, 9.0f));
    for (int y = 0; y < h; ++y) EXPECT_FLOAT_EQ(got[(size_t(y) * w + 15) * 4], 2.0f) << "y " << y;
}

// Jitter end to end on builtin:cornell, still camera with the Halton jitter on: GBuffer samples at
// jittered positions (its albedo changes from frame to frame at edges) yet its motion is exactly
// 0, and TAA then fetches the history at the pixel centre, so its result is exactly the
// exponential moving average of the jittered frames (clip off) - the temporal supersampling.
TEST_F(TAATest, JitterFlowsThroughGBufferIntoTAA) {
    registerBuiltinPasses();
    const uint32_t n = 32;
    const scene::Scene cornell = scene::loadBuiltinScene("builtin:cornell");
    const scene::SceneGpu sceneGpu(ctx(), cornell);
    const std::string text = R"({ "version": 1, "name": "taa_jitter", "passes": [
        { "name": "gb", "type": "GBuffer" },
        { "name": "taa", "type": "TAA", "params": { "alpha": 0.125, "clip": "none" } } ],
      "edges": [ { "from": "gb.albedo", "to": "taa.color" }, { "from": "gb.motion", "to": "taa.motion" } ],
      "outputs": [ "taa.result", "gb.albedo", "gb.motion" ] })";
    CompileOptions o;
    o.width = o.height = n;
    o.sceneFeatures = sceneGpu.features();
    RenderGraph g(ctx(), passRegistry());
    g.setScene(&sceneGpu);
    g.build(parseGraphText(text, "taa_jitter"), o);
    scene::CameraRigOptions rig;
    rig.jitter = true;
    scene::FrameCamera previous;
    Image ema, first, got;
    size_t changedPixels = 0;
    for (uint64_t f = 0; f < 16; ++f) {
        scene::FrameCamera cam = scene::makeFrameCamera(cornell.cameras.at(0), n, n, rig, f,
                                                        f == 0 ? nullptr : &previous, nullptr);
        g.setCamera(cam);
        previous = cam;
        g.runFrame();
        const Image motion = g.image("gb.motion").downloadRGBA32F(ctx());
        for (size_t i = 0; i < motion.size(); i += 4)
            ASSERT_TRUE(motion[i] == 0.0f && motion[i + 1] == 0.0f) << "frame " << f;
        const Image albedo = g.image("gb.albedo").downloadRGBA32F(ctx());
        if (f == 0) {
            ema = first = albedo;
        } else {
            for (size_t i = 0; i < ema.size(); ++i)
                if (i % 4 != 3) ema[i] += 0.125f * (albedo[i] - ema[i]);
            for (size_t i = 0; i < albedo.size(); i += 4)
                if (albedo[i] != first[i] || albedo[i + 1] != first[i + 1]) ++changedPixels;
        }
        got = g.image("taa.result").downloadRGBA32F(ctx());
        ASSERT_TRUE(near(got, ema, 1e-5f)) << "frame " << f;
    }
    EXPECT_GT(changedPixels, 0u) << "the jitter never reached GBuffer";
}
