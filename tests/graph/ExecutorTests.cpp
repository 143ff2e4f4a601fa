// GPU tests of the render-graph executor (core/graph/RenderGraph*.cpp) with the built-in utility
// passes: exact pixels, delayed edges and history validity across reset / resize / rebuild,
// caching, bypass, aliasing on and off, Accumulate, and errors at build. Graphs come from
// graphs/tests/ or inline text; images are small and frames few (lavapipe). The fixture fails any
// test that produced a Vulkan validation message.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/util/Error.h"
#include "core/vk/Resources.h"
#include "passes/RegisterPasses.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::graph;

namespace {

namespace fs = std::filesystem;

fs::path testGraph(const std::string& name) {
    return fs::path(FOVEA_TEST_DIR) / ".." / "graphs" / "tests" / name;
}

CompileOptions sized(uint32_t width, uint32_t height, bool aliasing = true) {
    CompileOptions o;
    o.width = width;
    o.height = height;
    o.aliasing = aliasing;
    return o;
}

using Rgba = std::array<float, 4>;

// Checks every channel of every pixel of an RGBA32F download against expected(x, y), within
// `tolerance` (0: bit-exact value comparison). Reports the first mismatch and how many there are.
::testing::AssertionResult pixelsMatch(const std::vector<float>& px, uint32_t width,
                                       uint32_t height,
                                       const std::function<Rgba(uint32_t, uint32_t)>& expected,
                                       float tolerance = 0.0f) {
    if (px.size() != size_t(width) * height * 4)
        return ::testing::AssertionFailure()
               << "got " << px.size() << " floats for " << width << "x" << height;
    size_t bad = 0;
    std::ostringstream first;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            Rgba e = expected(x, y);
            for (int c = 0; c < 4; ++c) {
                float got = px[(size_t(y) * width + x) * 4 + c];
                if (std::fabs(got - e[c]) <= tolerance) continue;
                if (bad++ == 0)
                    first << "pixel (" << x << ", " << y << ") channel " << c << ": got " << got
                          << ", expected " << e[c];
            }
        }
    if (bad == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << bad << " channel values differ; first: " << first.str();
}

::testing::AssertionResult allPixels(const std::vector<float>& px, uint32_t width, uint32_t height,
                                     Rgba value, float tolerance = 0.0f) {
    return pixelsMatch(
        px, width, height, [&](uint32_t, uint32_t) { return value; }, tolerance);
}

Rgba splat(float v) {
    return {v, v, v, v};
}

class ExecutorTest : public GpuTest {
protected:
    static void SetUpTestSuite() { registerBuiltinPasses(); }

    static std::unique_ptr<RenderGraph> makeGraph(const GraphDesc& desc,
                                                  const CompileOptions& options) {
        auto g = std::make_unique<RenderGraph>(ctx(), passRegistry());
        g->build(desc, options);
        return g;
    }

    static std::vector<float> pixels(const RenderGraph& g, const std::string& resource) {
        return g.image(resource).downloadRGBA32F(ctx());
    }

    static const PassRecord& record(const RenderGraph& g, const std::string& pass) {
        size_t n = g.plan().findNode(pass);
        EXPECT_NE(n, kNone) << "no pass " << pass;
        return g.records().at(n);
    }

    static bool historyValid(const RenderGraph& g, const std::string& pass,
                             const std::string& input) {
        return g.historyValidFor(g.plan().findNode(pass), input, 1);
    }
};

class ExecutorUtility : public ExecutorTest {};
class ExecutorHistory : public ExecutorTest {};
class ExecutorCache : public ExecutorTest {};
class ExecutorBypass : public ExecutorTest {};
class ExecutorAliasing : public ExecutorTest {};
class ExecutorAccumulate : public ExecutorTest {};
class ExecutorErrors : public ExecutorTest {};

// The gradient pattern of shaders/image_source/image_source.comp for value (vx, vy, vz):
// uv = (p + 0.5) / size; (u, v, 1 - u, 1) * (value, 1).
Rgba gradient(uint32_t x, uint32_t y, uint32_t w, uint32_t h, Rgba value) {
    float u = (float(x) + 0.5f) / float(w), v = (float(y) + 0.5f) / float(h);
    return {u * value[0], v * value[1], (1.0f - u) * value[2], 1.0f};
}

// shaders/common/color.glsl linearToSrgb, then unorm8 quantisation.
float srgb8(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    float s = c < 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return std::round(std::clamp(s, 0.0f, 1.0f) * 255.0f) / 255.0f;
}

}  // namespace

// --- 1. exact pixels of the utility passes ------------------------------------------------------

TEST_F(ExecutorUtility, ConstantGradientBlitCombineGiveExactPixels) {
    GraphDesc desc = parseGraphFile(testGraph("utility_exact.json"));
    ASSERT_TRUE(desc.defaults.size.has_value());
    const uint32_t w = (*desc.defaults.size)[0], h = (*desc.defaults.size)[1];
    ASSERT_NE(w, h) << "a non-square size catches swapped axes";
    auto g = makeGraph(desc, sized(w, h));
    g->runFrame();
    for (const char* pass : {"constant", "gradient", "up", "diff"}) {
        EXPECT_EQ(record(*g, pass).status, PassStatus::Executed) << pass;
        EXPECT_EQ(record(*g, pass).executions, 1u) << pass;
    }

    const Rgba constant = {0.25f, -1.5f, 3.0f, 1.0f};
    EXPECT_TRUE(allPixels(pixels(*g, "constant.color"), w, h, constant));

    // The shader divides on the GPU: allow a couple of ulps (values are <= 2).
    std::vector<float> grad = pixels(*g, "gradient.color");
    auto expectedGradient = [&](uint32_t x, uint32_t y) {
        return gradient(x, y, w, h, {1.0f, 2.0f, 0.5f, 1.0f});
    };
    EXPECT_TRUE(pixelsMatch(grad, w, h, expectedGradient, 5e-7f));
    // Spot-check the formula itself at the corners (not just self-consistency).
    EXPECT_NEAR(grad[0], 0.5f / w, 1e-7);
    EXPECT_NEAR(grad[1], 2.0f * 0.5f / h, 1e-7);
    EXPECT_NEAR(grad[2], 0.5f * (1.0f - 0.5f / w), 1e-7);
    size_t last = (size_t(h) * w - 1) * 4;
    EXPECT_NEAR(grad[last + 0], (w - 0.5f) / w, 1e-6);
    EXPECT_NEAR(grad[last + 1], 2.0f * (h - 0.5f) / h, 1e-6);

    // Nearest 2x upsampling: destination pixel (x, y) samples at source ((x + 0.5) / 2), so it
    // is source texel (x / 2, y / 2) copied bit for bit (no boundary cases at 2x).
    const gpu::Image& up = g->image("up.result");
    ASSERT_EQ(up.width(), 2 * w);
    ASSERT_EQ(up.height(), 2 * h);
    EXPECT_TRUE(pixelsMatch(up.downloadRGBA32F(ctx()), 2 * w, 2 * h, [&](uint32_t x, uint32_t y) {
        const float* p = &grad[(size_t(y / 2) * w + x / 2) * 4];
        return Rgba{p[0], p[1], p[2], p[3]};
    }));

    // |2 * constant - gradient| (alpha |2 - 1| = 1).
    EXPECT_TRUE(pixelsMatch(
        pixels(*g, "diff.result"), w, h,
        [&](uint32_t x, uint32_t y) {
            Rgba gr = expectedGradient(x, y), out;
            for (int c = 0; c < 4; ++c) out[c] = std::fabs(2.0f * constant[c] - gr[c]);
            return out;
        },
        1e-6f));
}

// --- 2 and 5. delayed edges and history validity ------------------------------------------------

// history_difference.json: diff = src - src(previous frame) with src = frame index; when the
// history is invalid Combine ignores b and the result is src alone (the frame index).
TEST_F(ExecutorHistory, DelayOneEdgeSeesThePreviousFrame) {
    auto g = makeGraph(parseGraphFile(testGraph("history_difference.json")), sized(16, 16));
    const ResourcePlan& src =
        g->plan().resources.at(g->plan().resourceOf.at({g->plan().findNode("src"), "color"}));
    EXPECT_EQ(src.lifetime, Lifetime::History);
    EXPECT_EQ(src.ringSize, 2u);

    EXPECT_FALSE(historyValid(*g, "diff", "b"));
    EXPECT_TRUE(historyValid(*g, "diff", "a")) << "an undelayed input is always valid";
    g->runFrame();
    EXPECT_TRUE(allPixels(pixels(*g, "diff.result"), 16, 16, splat(0.0f))) << "frame 0";
    for (int frame = 1; frame < 4; ++frame) {
        EXPECT_TRUE(historyValid(*g, "diff", "b")) << "frame " << frame;
        g->runFrame();
        EXPECT_TRUE(allPixels(pixels(*g, "src.color"), 16, 16, splat(float(frame))));
        EXPECT_TRUE(allPixels(pixels(*g, "diff.result"), 16, 16, splat(1.0f))) << "frame " << frame;
    }
    EXPECT_EQ(g->frameIndex(), 4u);
    EXPECT_EQ(g->framesSinceReset(), 4u);
}

TEST_F(ExecutorHistory, ResetInvalidatesHistory) {
    auto g = makeGraph(parseGraphFile(testGraph("history_difference.json")), sized(16, 16));
    for (int i = 0; i < 3; ++i) g->runFrame();
    ASSERT_TRUE(allPixels(pixels(*g, "diff.result"), 16, 16, splat(1.0f)));
    ASSERT_TRUE(historyValid(*g, "diff", "b"));

    g->reset();
    EXPECT_EQ(g->framesSinceReset(), 0u);
    EXPECT_EQ(g->frameIndex(), 3u) << "reset does not rewind the frame index";
    EXPECT_FALSE(historyValid(*g, "diff", "b"));
    g->runFrame();
    // The ring holds frame 2's image, so a consumer that used it would see 3 - 2 = 1; with the
    // history invalid Combine uses a alone: the frame index, 3 (0 only on the very first frame).
    EXPECT_TRUE(allPixels(pixels(*g, "diff.result"), 16, 16, splat(3.0f)));
    EXPECT_TRUE(historyValid(*g, "diff", "b"));
    g->runFrame();
    EXPECT_TRUE(allPixels(pixels(*g, "diff.result"), 16, 16, splat(1.0f)));
    EXPECT_EQ(g->framesSinceReset(), 2u);
}

TEST_F(ExecutorHistory, ResizeInvalidatesHistory) {
    auto g = makeGraph(parseGraphFile(testGraph("history_difference.json")), sized(16, 16));
    for (int i = 0; i < 2; ++i) g->runFrame();
    ASSERT_TRUE(historyValid(*g, "diff", "b"));

    g->resize(8, 12);
    EXPECT_EQ(g->framesSinceReset(), 0u);
    EXPECT_FALSE(historyValid(*g, "diff", "b"));
    EXPECT_EQ(g->plan().options.width, 8u);
    EXPECT_EQ(g->plan().options.height, 12u);
    g->runFrame();
    const gpu::Image& out = g->image("diff.result");
    ASSERT_EQ(out.width(), 8u);
    ASSERT_EQ(out.height(), 12u);
    EXPECT_TRUE(allPixels(out.downloadRGBA32F(ctx()), 8, 12, splat(2.0f)));
    EXPECT_TRUE(historyValid(*g, "diff", "b"));
    g->runFrame();
    EXPECT_TRUE(allPixels(pixels(*g, "diff.result"), 8, 12, splat(1.0f)));

    // Resizing to the size it already has still invalidates (resize = rebuild + reset).
    g->resize(8, 12);
    EXPECT_EQ(g->framesSinceReset(), 0u);
    EXPECT_FALSE(historyValid(*g, "diff", "b"));
    g->runFrame();
    EXPECT_TRUE(allPixels(pixels(*g, "diff.result"), 8, 12, splat(4.0f)));
}

TEST_F(ExecutorHistory, UnchangedRebuildKeepsHistoryRings) {
    GraphDesc desc = parseGraphFile(testGraph("history_difference.json"));
    auto g = makeGraph(desc, sized(16, 16));
    for (int i = 0; i < 2; ++i) g->runFrame();
    const gpu::Image* ringSlot = &g->image("src.color");
    const uint64_t persistent = g->allocatedPersistentBytes();

    g->build(desc, sized(16, 16));
    EXPECT_EQ(g->framesSinceReset(), 2u);
    EXPECT_TRUE(historyValid(*g, "diff", "b"));
    EXPECT_EQ(&g->image("src.color"), ringSlot) << "the ring was reallocated";
    EXPECT_EQ(g->allocatedPersistentBytes(), persistent);
    g->runFrame();
    // 2 - 1: the kept ring still holds frame 1's image (a fresh, zeroed one would give 2).
    EXPECT_TRUE(allPixels(pixels(*g, "diff.result"), 16, 16, splat(1.0f)));

    // A rebuild at another size is a resize: the ring is new and the history invalid.
    g->build(desc, sized(8, 8));
    EXPECT_EQ(g->framesSinceReset(), 0u);
    EXPECT_FALSE(historyValid(*g, "diff", "b"));
}

// A rebuild that needs a different ring (here: a longer delay) allocates a fresh, zeroed one:
// there is no history from d frames ago in it, whatever framesSinceReset says.
TEST_F(ExecutorHistory, RebuildWithNewRingInvalidatesItsHistory) {
    GraphDesc desc = parseGraphFile(testGraph("history_difference.json"));
    auto g = makeGraph(desc, sized(16, 16));
    for (int i = 0; i < 2; ++i) g->runFrame();
    ASSERT_TRUE(historyValid(*g, "diff", "b"));

    ASSERT_EQ(desc.edges.at(1).to.str(), "diff.b");
    desc.edges.at(1).delay = 2;
    g->build(desc, sized(16, 16));
    EXPECT_EQ(g->plan()
                  .resources.at(g->plan().resourceOf.at({g->plan().findNode("src"), "color"}))
                  .ringSize,
              3u);
    for (uint64_t frame = 2; frame < 4; ++frame) {
        EXPECT_FALSE(historyValid(*g, "diff", "b")) << "frame " << frame;
        g->runFrame();
        EXPECT_TRUE(allPixels(pixels(*g, "diff.result"), 16, 16, splat(float(frame))));
    }
    EXPECT_TRUE(historyValid(*g, "diff", "b"));
    g->runFrame();  // frame 4 - frame 2, both written into the new ring
    EXPECT_TRUE(allPixels(pixels(*g, "diff.result"), 16, 16, splat(2.0f)));
}

// --- 3. caching ----------------------------------------------------------------------------------

TEST_F(ExecutorCache, CacheablePassesRunOnce) {
    auto g = makeGraph(parseGraphFile(testGraph("cached_source.json")), sized(16, 8));
    g->runFrame();
    EXPECT_EQ(record(*g, "src").status, PassStatus::Executed);
    EXPECT_EQ(record(*g, "tm").status, PassStatus::Executed);
    const int frames = 4;
    for (int i = 1; i < frames; ++i) g->runFrame();
    for (const char* pass : {"src", "tm"}) {
        const PassRecord& r = record(*g, pass);
        EXPECT_EQ(r.status, PassStatus::Cached) << pass;
        EXPECT_EQ(r.executions, 1u) << pass;
        EXPECT_EQ(r.gpuMs.size(), 1u) << pass << ": timings only for frames it ran";
        EXPECT_FALSE(r.reason.empty()) << pass;
    }
    // The cached (persistent) output still holds the tone-mapped gradient.
    EXPECT_TRUE(pixelsMatch(
        pixels(*g, "tm.ldr"), 16, 8,
        [](uint32_t x, uint32_t y) {
            Rgba c = gradient(x, y, 16, 8, {1, 1, 1, 1});
            return Rgba{srgb8(c[0]), srgb8(c[1]), srgb8(c[2]), 1.0f};
        },
        1.01f / 255.0f));

    // reset() drops the caches: both run once more, then are cached again.
    g->reset();
    g->runFrame();
    EXPECT_EQ(record(*g, "src").status, PassStatus::Executed);
    EXPECT_EQ(record(*g, "src").executions, 2u);
    EXPECT_EQ(record(*g, "tm").executions, 2u);
    g->runFrame();
    EXPECT_EQ(record(*g, "src").status, PassStatus::Cached);
    EXPECT_EQ(record(*g, "tm").executions, 2u);
}

// A cacheable pass whose input changes every frame runs every frame.
TEST_F(ExecutorCache, ChangedInputDefeatsTheCache) {
    auto g = makeGraph(parseGraphText(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "ImageSource", "params": { "pattern": "frame-index" } },
                  { "name": "tm", "type": "Tonemap" } ],
      "edges": [ { "from": "src.color", "to": "tm.color" } ],
      "outputs": [ "tm.ldr" ] })",
                                      "frame_tonemap.json"),
                       sized(8, 8));
    g->runFrame();
    EXPECT_TRUE(allPixels(pixels(*g, "tm.ldr"), 8, 8, {0, 0, 0, 0}));
    g->runFrame();
    EXPECT_TRUE(allPixels(pixels(*g, "tm.ldr"), 8, 8, splat(1.0f))) << "a stale cache gives 0";
    g->runFrame();
    EXPECT_EQ(record(*g, "tm").status, PassStatus::Executed);
    EXPECT_EQ(record(*g, "tm").executions, 3u);
}

// The noise pattern depends on the run's seed: changing it must not serve the cached image.
TEST_F(ExecutorCache, SeedChangeRerunsCachedNoise) {
    auto g = makeGraph(parseGraphText(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "ImageSource", "params": { "pattern": "noise" } } ],
      "outputs": [ "src.color" ] })",
                                      "noise.json"),
                       sized(8, 8));
    g->setSeed(1);
    g->runFrame();
    g->runFrame();
    ASSERT_EQ(record(*g, "src").status, PassStatus::Cached);
    std::vector<float> before = pixels(*g, "src.color");
    g->setSeed(2);
    g->runFrame();
    EXPECT_EQ(record(*g, "src").status, PassStatus::Executed);
    EXPECT_NE(pixels(*g, "src.color"), before);
}

// --- 4. bypass -----------------------------------------------------------------------------------

TEST_F(ExecutorBypass, InactiveFramesCopyTheInput) {
    auto g = makeGraph(parseGraphFile(testGraph("bypass_every_other.json")), sized(16, 16));
    const int frames = 5;
    for (int frame = 0; frame < frames; ++frame) {
        g->runFrame();
        const PassRecord& blit = record(*g, "blit");
        EXPECT_EQ(blit.status, frame % 2 == 0 ? PassStatus::Executed : PassStatus::Bypassed)
            << "frame " << frame;
        // Executed or bypassed, the output is this frame's input (a pass that merely kept its
        // previous content would show frame - 1).
        std::vector<float> out = pixels(*g, "blit.result");
        EXPECT_TRUE(allPixels(out, 16, 16, splat(float(frame)))) << "frame " << frame;
        EXPECT_EQ(out, pixels(*g, "src.color")) << "frame " << frame;
    }
    EXPECT_EQ(record(*g, "blit").executions, 3u);
    EXPECT_EQ(record(*g, "blit").gpuMs.size(), size_t(frames)) << "executed + bypassed frames";
    EXPECT_EQ(record(*g, "src").executions, uint64_t(frames));
}

// --- 6. aliasing ---------------------------------------------------------------------------------

TEST_F(ExecutorAliasing, OnAndOffGiveBitIdenticalImages) {
    GraphDesc desc = parseGraphFile(testGraph("chain20.json"));
    auto aliased = makeGraph(desc, sized(32, 32, true));
    auto separate = makeGraph(desc, sized(32, 32, false));
    EXPECT_FALSE(aliased->plan().aliasGroups.empty());
    EXPECT_TRUE(separate->plan().aliasGroups.empty());
    // src.color lives through the whole chain, the 18 Combine results alternate between two
    // blocks: 3 transient images instead of 19 (tm.ldr is persistent: Tonemap is cacheable).
    EXPECT_LT(aliased->allocatedTransientBytes(), separate->allocatedTransientBytes());
    EXPECT_LE(aliased->allocatedTransientBytes() * 6, separate->allocatedTransientBytes())
        << aliased->allocatedTransientBytes() << " vs " << separate->allocatedTransientBytes();
    EXPECT_EQ(aliased->allocatedPersistentBytes(), separate->allocatedPersistentBytes());

    auto raw = [&](const RenderGraph& g, const std::string& name) {
        return g.image(name).download(ctx());
    };
    for (int frame = 0; frame < 3; ++frame) {
        aliased->runFrame();
        separate->runFrame();
        for (const char* name : {"tm.ldr", "c17.result", "src.color"})
            EXPECT_TRUE(raw(*aliased, name) == raw(*separate, name))
                << name << " differs at frame " << frame;
        // Each Combine is 0.5 * prev + 0.5 * src with prev == src: exact, so the end of the
        // chain is the noise itself. (Since every link holds the same values, this graph cannot
        // show most wrong sharing; alias_mix.json below can.)
        std::vector<float> src = pixels(*aliased, "src.color");
        EXPECT_EQ(pixels(*aliased, "c17.result"), src) << "frame " << frame;
        auto [lo, hi] = std::minmax_element(src.begin(), src.end());
        EXPECT_LT(*lo, 0.1f);
        EXPECT_GT(*hi, 0.9f);
    }
}

// Transients of three sizes whose values all differ, with a half-size Blit that reads other
// pixels than it writes: any two overlapping lifetimes wrongly sharing memory change c4.
TEST_F(ExecutorAliasing, MixedSizesAndLifetimesBitIdentical) {
    GraphDesc desc = parseGraphFile(testGraph("alias_mix.json"));
    auto aliased = makeGraph(desc, sized(32, 32, true));
    auto separate = makeGraph(desc, sized(32, 32, false));
    size_t transients = 0, shared = 0;
    for (const auto& r : aliased->plan().resources)
        if (r.lifetime == Lifetime::Transient) ++transients;
    for (const auto& g : aliased->plan().aliasGroups)
        if (g.members.size() > 1) shared += g.members.size();
    EXPECT_EQ(transients, 7u);
    EXPECT_LT(aliased->plan().aliasGroups.size(), transients);
    EXPECT_GE(shared, 2u) << "some transients share memory";
    EXPECT_LT(aliased->allocatedTransientBytes(), separate->allocatedTransientBytes());

    for (int frame = 0; frame < 3; ++frame) {
        aliased->runFrame();
        separate->runFrame();
        std::vector<float> a = pixels(*aliased, "c4.result"), b = pixels(*separate, "c4.result");
        EXPECT_TRUE(aliased->image("c4.result").download(ctx()) ==
                    separate->image("c4.result").download(ctx()))
            << "frame " << frame;
        auto [lo, hi] = std::minmax_element(b.begin(), b.end());
        EXPECT_LT(*lo, *hi - 1.0f) << "the output is not flat";
    }
}

// --- 7. Accumulate ------------------------------------------------------------------------------

TEST_F(ExecutorAccumulate, MeanOfFrameIndices) {
    auto g = makeGraph(parseGraphFile(testGraph("accumulate_frame_index.json")), sized(16, 16));
    const int frames = 8;
    for (int n = 1; n <= frames; ++n) {
        g->runFrame();
        if (n == 1 || n == 4 || n == frames) {  // mean of 0..n-1
            EXPECT_TRUE(allPixels(pixels(*g, "acc.mean"), 16, 16, splat((n - 1) / 2.0f), 1e-5f))
                << "after " << n << " frames";
        }
    }
    EXPECT_TRUE(allPixels(pixels(*g, "acc.count"), 16, 16, {float(frames), 0, 0, 1}));
    EXPECT_EQ(record(*g, "acc").executions, uint64_t(frames));

    // After a reset the mean restarts: frames 8..11 average to 9.5.
    g->reset();
    for (int i = 0; i < 4; ++i) g->runFrame();
    EXPECT_TRUE(allPixels(pixels(*g, "acc.mean"), 16, 16, splat(9.5f), 1e-5f));
    EXPECT_TRUE(allPixels(pixels(*g, "acc.count"), 16, 16, {4, 0, 0, 1}));
}

TEST_F(ExecutorAccumulate, MaxFramesFreezesTheMean) {
    GraphDesc desc = parseGraphFile(testGraph("accumulate_frame_index.json"));
    desc.passes.at(1).params["maxFrames"] = 3;
    auto g = makeGraph(desc, sized(8, 8));
    for (int i = 0; i < 6; ++i) g->runFrame();
    const PassRecord& acc = record(*g, "acc");
    EXPECT_EQ(acc.status, PassStatus::Skipped);
    EXPECT_EQ(acc.executions, 3u);
    EXPECT_TRUE(allPixels(pixels(*g, "acc.mean"), 8, 8, splat(1.0f), 1e-5f)) << "mean of 0, 1, 2";
    EXPECT_TRUE(allPixels(pixels(*g, "acc.count"), 8, 8, {3, 0, 0, 1}));
}

namespace {

// Accumulate whose mean is also read one frame late: delta = mean - previous mean.
const char* kAccumulateDelta = R"({ "version": 1,
  "passes": [ { "name": "src", "type": "ImageSource", "params": { "pattern": "frame-index" } },
              { "name": "acc", "type": "Accumulate" },
              { "name": "delta", "type": "Combine", "params": { "weightA": 1, "weightB": -1 } } ],
  "edges": [ { "from": "src.color", "to": "acc.color" }, { "from": "acc.mean", "to": "delta.a" },
             { "from": "acc.mean", "to": "delta.b", "delay": 1 } ],
  "outputs": [ "acc.mean", "delta.result" ] })";

}  // namespace

// Accumulate's mean is persistent (read-modify-write across frames). Consuming it through a
// delayed edge makes it a history ring, and each frame then writes another ring slot: the
// running mean must still continue from the previous frame's value.
TEST_F(ExecutorAccumulate, MeanWithADelayedConsumer) {
    auto g = makeGraph(parseGraphText(kAccumulateDelta, "accumulate_delta.json"), sized(8, 8));
    ASSERT_EQ(g->plan()
                  .resources.at(g->plan().resourceOf.at({g->plan().findNode("acc"), "mean"}))
                  .lifetime,
              Lifetime::History);
    for (int n = 1; n <= 4; ++n) {
        g->runFrame();
        EXPECT_TRUE(allPixels(pixels(*g, "acc.mean"), 8, 8, splat((n - 1) / 2.0f), 1e-5f))
            << "after " << n << " frames";
        if (n > 1) {  // the mean grows by 1/2 per frame
            EXPECT_TRUE(allPixels(pixels(*g, "delta.result"), 8, 8, splat(0.5f), 1e-5f))
                << "after " << n << " frames";
        }
    }
}

// The same with maxFrames: once Accumulate is skipped its ring output keeps the last mean.
TEST_F(ExecutorAccumulate, SkippedPassKeepsItsHistoryRingOutput) {
    GraphDesc desc = parseGraphText(kAccumulateDelta, "accumulate_delta.json");
    desc.passes.at(1).params["maxFrames"] = 2;
    auto g = makeGraph(desc, sized(8, 8));
    for (int n = 1; n <= 5; ++n) {
        g->runFrame();
        EXPECT_EQ(record(*g, "acc").status, n <= 2 ? PassStatus::Executed : PassStatus::Skipped);
        EXPECT_TRUE(allPixels(pixels(*g, "acc.mean"), 8, 8, splat(n == 1 ? 0.0f : 0.5f), 1e-5f))
            << "after " << n << " frames";
        if (n > 2) {
            EXPECT_TRUE(allPixels(pixels(*g, "delta.result"), 8, 8, splat(0.0f)))
                << "after " << n << " frames";
        }
    }
}

// --- 8. errors at build --------------------------------------------------------------------------

namespace {

std::string buildError(RenderGraph& g, const std::string& text, const CompileOptions& o) {
    try {
        g.build(parseGraphText(text, "bad.json"), o);
    } catch (const InputError& e) {
        return e.what();
    }
    return "<no error>";
}

std::string blitGraph(const std::string& blitParams) {
    return R"({ "version": 1,
      "passes": [ { "name": "src", "type": "ImageSource" },
                  { "name": "blit", "type": "Blit", "params": )" +
           blitParams + R"( } ],
      "edges": [ { "from": "src.color", "to": "blit.color" } ],
      "outputs": [ "blit.result" ] })";
}

}  // namespace

TEST_F(ExecutorErrors, BypassBetweenDifferentSizeOrFormatIsRejected) {
    RenderGraph g(ctx(), passRegistry());
    EXPECT_EQ(buildError(g, blitGraph(R"({ "activeEvery": 2, "scale": 0.5 })"), sized(16, 16)),
              "bad.json: /passes/1: pass 'blit' bypasses 'color' into 'result' but they differ "
              "in size or format");
    EXPECT_EQ(
        buildError(g, blitGraph(R"({ "activeEvery": 2, "format": "rgba16f" })"), sized(16, 16)),
        "bad.json: /passes/1: pass 'blit' bypasses 'color' into 'result' but they differ "
        "in size or format");
    // Without a bypass (activeEvery 1) the same resampling is fine, and so is a bypass between
    // equal size and format; the graph object recovers from the failed builds.
    EXPECT_EQ(buildError(g, blitGraph(R"({ "scale": 0.5, "format": "rgba16f" })"), sized(16, 16)),
              "<no error>");
    EXPECT_EQ(buildError(g, blitGraph(R"({ "activeEvery": 2 })"), sized(16, 16)), "<no error>");
    g.runFrame();
    g.runFrame();
    EXPECT_EQ(record(g, "blit").status, PassStatus::Bypassed);
}

// A graph that fails to compile leaves the running graph as it was (plan, resources, history).
TEST_F(ExecutorErrors, CompileErrorLeavesTheGraphRunning) {
    auto g = makeGraph(parseGraphFile(testGraph("history_difference.json")), sized(16, 16));
    for (int i = 0; i < 2; ++i) g->runFrame();
    // Combine's b must match a's size: a half-size Blit into it is a compile error.
    std::string error = buildError(*g, R"({ "version": 1,
      "passes": [ { "name": "src", "type": "ImageSource" },
                  { "name": "half", "type": "Blit", "params": { "scale": 0.5 } },
                  { "name": "diff", "type": "Combine" } ],
      "edges": [ { "from": "src.color", "to": "half.color" }, { "from": "src.color", "to": "diff.a" },
                 { "from": "half.result", "to": "diff.b" } ],
      "outputs": [ "diff.result" ] })",
                                   sized(16, 16));
    EXPECT_NE(error.find("bad.json: /edges/2: size mismatch"), std::string::npos) << error;
    EXPECT_EQ(g->plan().nodes.size(), 2u);
    EXPECT_EQ(g->framesSinceReset(), 2u);
    g->runFrame();
    EXPECT_TRUE(allPixels(pixels(*g, "diff.result"), 16, 16, splat(1.0f)));
}
