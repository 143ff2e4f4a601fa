// GPU tests of the ATrousNH pass (seed 000 §3.4, Eq. 2, Algorithm 1): the GPU output equals the
// scalar CPU reference (tests/graph/ATrousReference) on random inputs and masks, mono 32x32 and
// stereo 48x24; unsampled pixels never leak; no holes and no darkening with sparse masks; no tap
// crosses the eye seam; one layer equals an independent classic à-trous; per-layer iteration
// counts are respected; with the Peres graphs' parameters every level up to the 5th lowers the
// error on a noisy wall and NH2LD differs from NH3LD. Inputs come from a no-op "Feed" pass whose
// persistent outputs the test uploads before the frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/vk/Resources.h"
#include "passes/ATrousNH/ATrousNHPass.h"
#include "tests/graph/ATrousReference.h"
#include "tests/graph/ATrousTestInputs.h"
#include "tests/passes/FeedPass.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::graph;
using fovea::passes::ATrousDispatch;
using fovea::passes::ATrousScheduleOptions;
using fovea::passes::buildATrousSchedule;

namespace {

const PassRegistry& registry() {
    return test::atrousFeedRegistry();
}

using Inputs = test::ATrousInputs;

// Concentric layers around each eye's centre (radii 0.2 / 0.4 of the eye height, like
// FoveationMask), sampled with probability 1 / pMiddle / pOuter.
Inputs randomInputs(int width, int height, int eyes, float pMiddle, float pOuter, uint32_t seed) {
    return test::layeredATrousInputs(width, height, eyes, {0.5f, 0.5f, 0.2f, 0.4f, pMiddle, pOuter},
                                     seed);
}

class ATrousNHTest : public GpuTest {
protected:
    // Builds Feed -> ATrousNH with `params` (a JSON object), uploads `in`, runs one frame and
    // returns the denoised image. `useMask` / `useGeometry` decide which edges exist.
    static std::vector<float> run(const Inputs& in, const std::string& params, bool useMask,
                                  bool useGeometry = true,
                                  std::vector<float>* normalUsed = nullptr) {
        std::string edges = R"({ "from": "feed.color", "to": "dn.color" })";
        if (useGeometry)
            edges += R"(, { "from": "feed.normal", "to": "dn.normal" },
                        { "from": "feed.position", "to": "dn.position" })";
        if (useMask) edges += R"(, { "from": "feed.mask", "to": "dn.mask" })";
        const std::string text =
            R"({ "version": 1, "name": "atrous_nh_test", "passes": [ { "name": "feed", )"
            R"("type": "Feed" }, { "name": "dn", "type": "ATrousNH", "params": )" +
            params + R"( } ], "edges": [ )" + edges + R"( ], "outputs": [ "dn.denoised" ] })";
        CompileOptions o;
        o.width = uint32_t(in.width);
        o.height = uint32_t(in.height);
        RenderGraph g(ctx(), registry());
        g.build(parseGraphText(text, "atrous_nh_test"), o);
        // The graph hands out const images; these are ordinary (non-const) graph resources, and
        // Feed never writes them, so the test fills them from the host before the frame.
        auto target = [&](const char* name) -> gpu::Image& {
            return const_cast<gpu::Image&>(g.image(name));
        };
        target("feed.color").uploadRGBA32F(ctx(), in.color);
        if (useGeometry) {
            target("feed.normal").uploadRGBA32F(ctx(), in.normal);
            target("feed.position").uploadRGBA32F(ctx(), in.position);
            // The reference must see the fp16-rounded normals the shader reads.
            if (normalUsed) *normalUsed = g.image("feed.normal").downloadRGBA32F(ctx());
        }
        if (useMask)
            target("feed.mask").upload(ctx(), in.mask.data(), in.mask.size() * sizeof(uint32_t));
        g.runFrame();
        return g.image("dn.denoised").downloadRGBA32F(ctx());
    }

    static testref::ATrousRefInput refInput(const Inputs& in, int eyes, int layers,
                                            const ATrousScheduleOptions& so, bool useMask,
                                            const std::vector<float>& normal) {
        testref::ATrousRefInput r;
        r.width = in.width;
        r.height = in.height;
        r.eyes = eyes;
        r.layerCount = layers;
        r.color = in.color;
        r.normal = normal;
        r.position = in.position;
        if (useMask) r.mask = in.mask;
        r.schedule = buildATrousSchedule(so);
        return r;
    }
};

::testing::AssertionResult near(const std::vector<float>& got, const std::vector<float>& want,
                                float tolerance) {
    if (got.size() != want.size())
        return ::testing::AssertionFailure() << got.size() << " vs " << want.size() << " floats";
    size_t bad = 0, first = 0;
    for (size_t i = 0; i < got.size(); ++i)
        if (!(std::fabs(got[i] - want[i]) <= tolerance) && bad++ == 0) first = i;
    if (bad == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure()
           << bad << " values differ; first: pixel " << first / 4 << " channel " << first % 4
           << ": " << got[first] << " vs " << want[first];
}

ATrousScheduleOptions options(int layers, int m, int nn, int p, bool decreasing, bool perLayer,
                              bool fill, int reach) {
    ATrousScheduleOptions o;
    o.layerCount = layers;
    o.iterations[0] = m;
    o.iterations[1] = nn;
    o.iterations[2] = p;
    o.decreasing = decreasing;
    o.perLayer = perLayer;
    o.fill = fill;
    o.fillReach = reach;
    return o;
}

}  // namespace

// --- schedule (CPU) -----------------------------------------------------------------------------

TEST(ATrousNHSchedule, PerLayerIterationCountsAndStepOrder) {
    for (bool perLayer : {false, true})
        for (bool decreasing : {false, true}) {
            auto s = buildATrousSchedule(options(3, 2, 3, 5, decreasing, perLayer, false, 1));
            const int want[3] = {2, 3, 5};
            for (int l = 0; l < 3; ++l) {
                std::vector<int> steps;
                for (const ATrousDispatch& d : s)
                    if ((d.layers >> l) & 1u) steps.push_back(d.step);
                ASSERT_EQ(int(steps.size()), want[l]) << "layer " << l;
                for (int j = 0; j < want[l]; ++j)  // Algorithm 1: 2^(n-1) .. 1, or reversed
                    EXPECT_EQ(steps[j], 1 << (decreasing ? want[l] - 1 - j : j)) << "layer " << l;
            }
            EXPECT_EQ(s.size(), perLayer ? 10u : 5u);
        }
    // Fill levels reach the whole eye: radius 2 (2^(k+1) - 1) >= reach after the last one.
    auto f = buildATrousSchedule(options(1, 0, 0, 0, true, false, true, 100));
    ASSERT_FALSE(f.empty());
    EXPECT_TRUE(f.back().fill);
    EXPECT_GE(2 * (2 * f.back().step - 1), 100);
    EXPECT_LT(2 * (f.back().step - 1), 100);  // and not one level more than needed
    // Nothing to do is still one (copy) dispatch, so the output is always written.
    EXPECT_EQ(buildATrousSchedule(options(2, 0, 0, 0, true, false, false, 1)).size(), 1u);
}

// --- GPU = CPU reference ------------------------------------------------------------------------

TEST_F(ATrousNHTest, MatchesReferenceMonoThreeLayersDecreasing) {
    Inputs in = randomInputs(32, 32, 1, 0.5f, 0.25f, 11);
    std::vector<float> normal;
    auto got = run(in,
                   R"({ "layers": 3, "iterations0": 1, "iterations1": 2, "iterations2": 3,
                        "eyes": 1 })",
                   true, true, &normal);
    auto want = testref::atrousReference(
        refInput(in, 1, 3, options(3, 1, 2, 3, true, false, true, 32), true, normal));
    EXPECT_TRUE(near(got, want, 1e-4f));
}

TEST_F(ATrousNHTest, MatchesReferenceStereoPerLayerIncreasing) {
    Inputs in = randomInputs(48, 24, 2, 0.4f, 0.2f, 12);
    std::vector<float> normal;
    auto got = run(in,
                   R"({ "layers": 3, "iterations0": 1, "iterations1": 2, "iterations2": 3,
                        "eyes": 2, "stepOrder": "increasing", "schedule": "layers",
                        "sigmaColor": 0.7, "sigmaNormal": 0.5, "sigmaPosition": 0.3,
                        "positionTerm": "distance" })",
                   true, true, &normal);
    auto r = refInput(in, 2, 3, options(3, 1, 2, 3, false, true, true, 24), true, normal);
    r.positionPlane = false;
    r.sigmaColor = 0.7f;
    r.sigmaNormal = 0.5f;
    r.sigmaPosition = 0.3f;
    EXPECT_TRUE(near(got, testref::atrousReference(r), 1e-4f));
}

// --- properties ---------------------------------------------------------------------------------

TEST_F(ATrousNHTest, UnsampledPixelsNeverLeak) {
    Inputs in = randomInputs(48, 24, 2, 0.5f, 0.25f, 13);
    const std::string params =
        R"({ "layers": 3, "iterations0": 1, "iterations1": 2, "iterations2": 3, "eyes": 2 })";
    auto clean = run(in, params, true);
    Inputs poisoned = in;
    size_t count = 0;
    for (size_t i = 0; i < in.mask.size(); ++i)
        if (!(in.mask[i] & 1u)) {
            ++count;
            for (int c = 0; c < 4; ++c) poisoned.color[i * 4 + c] = 1e6f;
        }
    ASSERT_GT(count, 100u);
    EXPECT_TRUE(near(run(in, params, true), clean, 0.0f));  // deterministic
    EXPECT_TRUE(near(run(poisoned, params, true), clean, 0.0f));
}

TEST_F(ATrousNHTest, NoHolesAndNoDarkeningWithSparseMask) {
    // 3% of the periphery sampled, one iteration per layer: most pixels have no sampled tap in
    // reach of the iterations; the fill levels must still give every pixel a value, and a
    // constant image must stay that constant (unsampled pixels do not count as black).
    Inputs in = randomInputs(48, 24, 2, 0.03f, 0.03f, 14);
    for (size_t i = 0; i < in.mask.size(); ++i)
        if (in.mask[i] & 1u)
            in.color[i * 4 + 0] = in.color[i * 4 + 1] = in.color[i * 4 + 2] = 0.75f;
    auto got = run(in, R"({ "layers": 3, "iterations0": 1, "iterations1": 1, "iterations2": 1,
                            "eyes": 2 })",
                   true);
    for (size_t i = 0; i < got.size() / 4; ++i) {
        ASSERT_EQ(got[i * 4 + 3], 1.0f) << "pixel " << i << " has no value";
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[i * 4 + c], 0.75f, 1e-5f) << "pixel " << i;
    }
    // Without the fill levels holes remain (so the test above can fail).
    auto holes = run(in, R"({ "layers": 3, "iterations0": 1, "iterations1": 1, "iterations2": 1,
                              "eyes": 2, "fill": false })",
                     true);
    size_t empty = 0;
    for (size_t i = 0; i < holes.size() / 4; ++i) empty += holes[i * 4 + 3] == 0.0f;
    EXPECT_GT(empty, 0u);
}

TEST_F(ATrousNHTest, SparseRandomColoursFiniteAndMatchReference) {
    Inputs in = randomInputs(48, 24, 2, 0.05f, 0.02f, 15);
    std::vector<float> normal;
    auto got = run(in, R"({ "layers": 3, "iterations0": 1, "iterations1": 2, "iterations2": 2,
                            "eyes": 2 })",
                   true, true, &normal);
    for (float v : got) ASSERT_TRUE(std::isfinite(v));
    for (size_t i = 0; i < got.size() / 4; ++i) ASSERT_EQ(got[i * 4 + 3], 1.0f);
    auto want = testref::atrousReference(
        refInput(in, 2, 3, options(3, 1, 2, 2, true, false, true, 24), true, normal));
    EXPECT_TRUE(near(got, want, 1e-4f));
}

TEST_F(ATrousNHTest, NoTapCrossesTheEyeSeam) {
    // Left eye 0, right eye 10, no edge weights: any cross-seam tap would mix them.
    Inputs in = randomInputs(48, 24, 2, 1.0f, 1.0f, 16);
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 48; ++x)
            for (int c = 0; c < 4; ++c)
                in.color[(size_t(y) * 48 + x) * 4 + c] = c == 3 ? 1.0f : (x < 24 ? 0.0f : 10.0f);
    auto got = run(in, R"({ "iterations0": 5, "eyes": 2, "sigmaColor": 0 })", false, false);
    for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 48; ++x)
            ASSERT_NEAR(got[(size_t(y) * 48 + x) * 4], x < 24 ? 0.0f : 10.0f, 1e-4f)
                << x << "," << y;  // one leaked tap would move it by >= 10/256
    // With one eye the same image does blur across the middle (the check above can fail).
    auto mono = run(in, R"({ "iterations0": 5, "eyes": 1, "sigmaColor": 0 })", false, false);
    EXPECT_GT(mono[(size_t(12) * 48 + 23) * 4], 0.1f);
}

// Dammertz et al. 2010 written out directly: full screen, every pixel valid, no mask or layers.
std::vector<float> classicATrous(const Inputs& in, const std::vector<float>& normal, int iterations,
                                 bool decreasing, float sc, float sn, float sx) {
    const float k[5] = {1.0f / 16, 1.0f / 4, 3.0f / 8, 1.0f / 4, 1.0f / 16};
    const int w = in.width, h = in.height;
    std::vector<float> c = in.color, next(c.size());
    auto d2 = [](const float* a, const float* b) {
        return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
               (a[2] - b[2]) * (a[2] - b[2]);
    };
    for (int it = 0; it < iterations; ++it) {
        int step = 1 << (decreasing ? iterations - 1 - it : it);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                size_t i = size_t(y) * w + x;
                float sum[3] = {0, 0, 0}, cum = 0;
                for (int dy = -2; dy <= 2; ++dy)
                    for (int dx = -2; dx <= 2; ++dx) {
                        int qx = x + step * dx, qy = y + step * dy;
                        if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
                        size_t j = size_t(qy) * w + qx;
                        float wt =
                            std::exp(-d2(&c[i * 4], &c[j * 4]) / (sc * sc)) *
                            std::exp(-d2(&normal[i * 4], &normal[j * 4]) /
                                     (float(step * step) * sn * sn)) *
                            std::exp(-d2(&in.position[i * 4], &in.position[j * 4]) / (sx * sx)) *
                            k[dx + 2] * k[dy + 2];
                        for (int ch = 0; ch < 3; ++ch) sum[ch] += c[j * 4 + ch] * wt;
                        cum += wt;
                    }
                for (int ch = 0; ch < 3; ++ch) next[i * 4 + ch] = sum[ch] / cum;  // cum > 0
                next[i * 4 + 3] = 1.0f;
            }
        c.swap(next);
    }
    return c;
}

TEST_F(ATrousNHTest, OneLayerEqualsClassicATrous) {
    Inputs in = randomInputs(32, 32, 1, 1.0f, 1.0f, 17);  // every pixel sampled
    for (bool decreasing : {true, false}) {
        const std::string order = decreasing ? "decreasing" : "increasing";
        const std::string params =
            R"({ "layers": 1, "iterations0": 4, "eyes": 1, "positionTerm": "distance",
                 "stepOrder": ")" +
            order + R"(" })";
        std::vector<float> normal;
        auto got = run(in, params, false, true, &normal);
        auto classic = classicATrous(in, normal, 4, decreasing, 1.0f, 0.2f, 0.5f);
        EXPECT_TRUE(near(got, classic, 1e-4f)) << order;
        // A connected mask with every pixel sampled changes nothing in one-layer mode, whatever
        // its layer ids.
        EXPECT_TRUE(near(run(in, params, true), got, 0.0f)) << order;
    }
}

TEST_F(ATrousNHTest, LayerIterationCountsRespected) {
    // Layer 1 has 0 iterations and no fill: its pixels keep their input exactly, while layers 0
    // and 2 (1 and 3 iterations) change; and the output matches the reference for these counts.
    Inputs in = randomInputs(32, 32, 1, 1.0f, 1.0f, 18);
    std::vector<float> normal;
    auto got = run(in, R"({ "layers": 3, "iterations0": 1, "iterations1": 0, "iterations2": 3,
                            "eyes": 1, "fill": false })",
                   true, true, &normal);
    size_t changed[3] = {0, 0, 0}, total[3] = {0, 0, 0};
    for (size_t i = 0; i < in.mask.size(); ++i) {
        int layer = int((in.mask[i] >> 1) & 3u);
        ++total[layer];
        bool same = true;
        for (int c = 0; c < 3; ++c) same = same && got[i * 4 + c] == in.color[i * 4 + c];
        changed[layer] += !same;
    }
    ASSERT_GT(total[1], 0u);
    EXPECT_EQ(changed[1], 0u);
    EXPECT_GT(changed[0], total[0] / 2);
    EXPECT_GT(changed[2], total[2] / 2);
    auto want = testref::atrousReference(
        refInput(in, 1, 3, options(3, 1, 0, 3, true, false, false, 32), true, normal));
    EXPECT_TRUE(near(got, want, 1e-4f));
}

TEST_F(ATrousNHTest, GpuDrivenFillLevelsMatchReferenceForOddAndEvenLevelCounts) {
    // Fill levels are indirect dispatches the GPU skips once no hole is left; an odd number of
    // executed levels leaves the result in `ping` and needs the copy-back. One valid pixel per
    // eye at different places needs different numbers of fill levels: both parities occur, and
    // every case must equal the reference that runs the whole schedule.
    std::set<int> parities;
    for (int place = 0; place < 4; ++place) {
        Inputs in = randomInputs(40, 24, 2, 1.0f, 1.0f, 20 + uint32_t(place));
        const int xs[4] = {0, 9, 5, 19}, ys[4] = {0, 12, 3, 23};
        for (int y = 0; y < in.height; ++y)
            for (int x = 0; x < in.width; ++x) {
                const bool keep = (x % 20 == xs[place]) && y == ys[place];
                if (!keep) in.mask[size_t(y * in.width + x)] &= ~1u;
            }
        for (int iterations : {0, 1}) {
            const std::string params = R"({ "layers": 1, "iterations0": )" +
                                       std::to_string(iterations) + R"(, "eyes": 2 })";
            std::vector<float> normal;
            auto got = run(in, params, true, true, &normal);
            auto r = refInput(in, 2, 1, options(1, iterations, 0, 0, true, false, true, 24), true,
                              normal);
            EXPECT_TRUE(near(got, testref::atrousReference(r), 1e-4f))
                << "place " << place << ", iterations " << iterations;
            for (size_t i = 0; i < got.size() / 4; ++i)
                ASSERT_EQ(got[i * 4 + 3], 1.0f) << "hole at pixel " << i << ", place " << place;
            // How many fill levels had holes to fill (the ones the GPU runs)?
            const auto full = r.schedule;
            int executed = 0;
            for (size_t n = 0; n < full.size(); ++n) {
                if (!full[n].fill) continue;
                r.schedule.assign(full.begin(), full.begin() + long(n));
                auto partial = testref::atrousReference(r);
                bool hole = false;
                for (size_t i = 0; i < partial.size() / 4; ++i) hole |= partial[i * 4 + 3] == 0.0f;
                if (!hole) break;
                ++executed;
            }
            parities.insert(executed % 2);
        }
    }
    EXPECT_EQ(parities.size(), 2u) << "the cases should cover odd and even fill-level counts";
}

TEST_F(ATrousNHTest, DepthRelativePositionUnitIsScaleInvariant) {
    // positionUnit = depth divides |x_p - x_q| by p's distance to its eye (the default camera's
    // eye is at the origin here), so scaling the scene by 100 leaves the output unchanged; with
    // scene units the same scaling changes it (so the test can fail).
    Inputs in = randomInputs(32, 32, 1, 0.6f, 0.4f, 31);
    for (size_t i = 0; i < in.position.size(); ++i)
        if (i % 4 != 3) in.position[i] += 3.0f;  // keep every point away from the eye
    Inputs scaled = in;
    for (size_t i = 0; i < scaled.position.size(); ++i)
        if (i % 4 != 3) scaled.position[i] *= 100.0f;
    const std::string depth = R"({ "layers": 3, "iterations0": 1, "iterations1": 2,
        "iterations2": 3, "eyes": 1, "positionUnit": "depth", "sigmaPosition": 0.05,
        "sigmaColor": 0 })";
    const std::string sceneUnits = R"({ "layers": 3, "iterations0": 1, "iterations1": 2,
        "iterations2": 3, "eyes": 1, "sigmaPosition": 0.2, "sigmaColor": 0 })";
    EXPECT_TRUE(near(run(scaled, depth, true), run(in, depth, true), 1e-4f));
    EXPECT_FALSE(near(run(scaled, sceneUnits, true), run(in, sceneUnits, true), 1e-3f));
}

// --- levels that matter (issue 15 §2) -----------------------------------------------------------

namespace {

// A 64x64 wall facing the default camera (eye at the origin, looking down -z) 3 units away, 2
// units wide: a smooth truth (a gentle ramp) plus seeded noise, every pixel sampled, the mask's
// three concentric layers as in randomInputs.
Inputs noisyWall(std::vector<float>& truth) {
    constexpr int kSize = 64;
    Inputs in = randomInputs(kSize, kSize, 1, 1.0f, 1.0f, 41);
    std::mt19937 rng(42);
    std::normal_distribution<float> noise(0.0f, 0.3f);
    truth.assign(in.color.size(), 1.0f);
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const size_t i = size_t(y) * kSize + x;
            const float u = (x + 0.5f) / kSize - 0.5f, v = (y + 0.5f) / kSize - 0.5f;
            const float base =
                1.0f + 0.05f * u - 0.025f * v;  // steeper: the 16 px level's bias wins
            for (int c = 0; c < 3; ++c) {
                truth[i * 4 + c] = base * (c == 1 ? 0.8f : 1.0f);
                in.color[i * 4 + c] = std::max(truth[i * 4 + c] + noise(rng), 0.0f);
                in.normal[i * 4 + c] = c == 2 ? 1.0f : 0.0f;
            }
            in.position[i * 4 + 0] = 2.0f * u;
            in.position[i * 4 + 1] = -2.0f * v;
            in.position[i * 4 + 2] = -3.0f;
        }
    return in;
}

// The "dn" (ATrousNH) params of a shipped graph, mono.
nlohmann::json denoiserParams(const std::string& graph) {
    std::ifstream file(std::string(FOVEA_TEST_DIR) + "/../graphs/" + graph);
    const auto root = nlohmann::json::parse(file);
    for (const auto& pass : root.at("passes"))
        if (pass.at("name") == "dn") {
            nlohmann::json p = pass.value("params", nlohmann::json::object());
            p["eyes"] = 1;
            // The graphs bound the reach along a surface (sigmaTangent, tuned against the
            // references: on Cornell a longer reach raised the error); unbounded here, so the test
            // checks that the plane term with the graphs' other sigmas lets every level act.
            p["sigmaTangent"] = 0;
            return p;
        }
    ADD_FAILURE() << graph << " has no pass 'dn'";
    return nlohmann::json::object();
}

double rmse(const std::vector<float>& a, const std::vector<float>& b) {
    double sum = 0;
    for (size_t i = 0; i < a.size(); ++i)
        if (i % 4 != 3) sum += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    return std::sqrt(sum / double(a.size() / 4 * 3));
}

}  // namespace

TEST_F(ATrousNHTest, EachLevelOfThePeresGraphsMattersAndNH2LDDiffersFromNH3LD) {
    // With Base's parameters (graphs/peres_base.json, reach along the surface unbounded) 1..5
    // iterations: each added level (the decreasing schedule adds the largest step, 2^(n-1) px)
    // changes the output by more than 1 % of the noise and lowers the error against the smooth
    // truth. Under the point-distance term the 16 px level is a no-op on such a wall (issue 15).
    constexpr double kMinChange = 0.01 * 0.3;  // 1 % of the noise; a no-op level changes ~0
    std::vector<float> truth;
    const Inputs in = noisyWall(truth);
    nlohmann::json base = denoiserParams("peres_base.json");
    std::vector<float> previous = in.color;
    double previousError = rmse(in.color, truth);
    for (int n = 1; n <= 5; ++n) {
        base["iterations0"] = n;
        const auto out = run(in, base.dump(), false);
        const double change = rmse(out, previous), error = rmse(out, truth);
        std::printf("Base, %d levels: RMSE %.4f, change from %d levels %.4f\n", n, error, n - 1,
                    change);
        EXPECT_GT(change, kMinChange) << n << " levels";
        EXPECT_LT(error, 0.97 * previousError) << n << " levels";
        previous = out;
        previousError = error;
    }
    nlohmann::json distance = base;
    distance["positionTerm"] = "distance";
    distance["iterations0"] = 4;
    const auto four = run(in, distance.dump(), false);
    distance["iterations0"] = 5;
    EXPECT_LT(rmse(run(in, distance.dump(), false), four), kMinChange)
        << "the point-distance term was expected to make the 16 px level a no-op";
    // NH2LD (two layers: middle + outer merged, N levels) vs NH3LD (three: N' < P): the
    // middle ring gets different level counts, so its outputs differ, and the one with more
    // levels is closer to the truth there.
    const auto nh2Params = denoiserParams("peres_nh2ld.json");
    const auto nh3Params = denoiserParams("peres_nh3ld.json");
    const int levels2 = nh2Params.value("iterations1", 0),
              levels3 = nh3Params.value("iterations1", 0);
    ASSERT_NE(levels2, levels3) << "NH2LD and NH3LD give the middle ring the same level count";
    const auto nh2 = run(in, nh2Params.dump(), true);
    const auto nh3 = run(in, nh3Params.dump(), true);
    std::vector<float> middle2, middle3, middleTruth;
    for (size_t i = 0; i < in.mask.size(); ++i)
        if (((in.mask[i] >> 1) & 3u) == 1u)
            for (int c = 0; c < 4; ++c) {
                middle2.push_back(nh2[i * 4 + c]);
                middle3.push_back(nh3[i * 4 + c]);
                middleTruth.push_back(truth[i * 4 + c]);
            }
    ASSERT_FALSE(middle2.empty());
    const double error2 = rmse(middle2, middleTruth), error3 = rmse(middle3, middleTruth);
    std::printf("middle ring: NH2LD (%d levels) RMSE %.4f, NH3LD (%d) %.4f, difference %.4f\n",
                levels2, error2, levels3, error3, rmse(middle2, middle3));
    EXPECT_GT(rmse(middle2, middle3), kMinChange);
    if (levels2 > levels3)
        EXPECT_LT(error2, error3);
    else
        EXPECT_LT(error3, error2);
}
