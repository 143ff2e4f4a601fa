// Sample layouts: the CPU side (core/sampling/SampleLayout.h: byte layout, parse, validation) and
// the SampleList pass on the GPU (patterns give the expected entries in row-major order, match
// the CPU builder exactly, are deterministic per seed and change per frame only when animated).
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/sampling/SampleLayout.h"
#include "core/util/Error.h"
#include "core/vk/Resources.h"
#include "passes/RegisterPasses.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::graph;
using sampling::SampleLayout;

namespace {

// --- CPU ------------------------------------------------------------------------------------

TEST(SampleLayoutCpu, BytesFollowTheStd430LayoutAndParseBack) {
    SampleLayout l;
    l.add(3, 5, 2);
    l.add(65535, 7, 9);
    const auto bytes = l.bytes();
    ASSERT_EQ(bytes.size(), 16u + 2u * 8u);
    uint32_t words[8];
    std::memcpy(words, bytes.data(), sizeof(words));
    EXPECT_EQ(words[0], 2u);               // count
    EXPECT_EQ(words[1], 9u);               // maxSamples
    EXPECT_EQ(words[4], 3u | (5u << 16));  // entries[0].x
    EXPECT_EQ(words[5], 2u);               // entries[0].y
    EXPECT_EQ(words[6], 65535u | (7u << 16));
    const SampleLayout back = SampleLayout::parse(bytes);
    ASSERT_EQ(back.entries.size(), 2u);
    EXPECT_EQ(sampling::unpackSamplePixel(back.entries[1].pixel), glm::uvec2(65535, 7));
    EXPECT_EQ(back.totalSamples(), 11u);
}

TEST(SampleLayoutCpu, ParseClampsTheCountAndRejectsAShortBuffer) {
    SampleLayout l;
    l.add(1, 1, 1);
    auto bytes = l.bytes();
    uint32_t hugeCount = 1000;
    std::memcpy(bytes.data(), &hugeCount, 4);
    EXPECT_EQ(SampleLayout::parse(bytes).entries.size(), 1u);
    EXPECT_THROW(SampleLayout::parse(std::vector<std::byte>(8)), RuntimeError);
}

TEST(SampleLayoutCpu, ValidationNamesBadEntries) {
    SampleLayout l;
    l.add(0, 0, 1);
    l.add(4, 0, 1);  // outside a 4x4 image
    l.add(1, 1, 0);  // zero samples
    l.add(0, 0, 2);  // duplicate
    const auto issues = sampling::validateSampleLayout(l, 4, 4);
    ASSERT_EQ(issues.size(), 3u);
    EXPECT_NE(issues[0].find("outside"), std::string::npos) << issues[0];
    EXPECT_NE(issues[1].find("sample count 0"), std::string::npos) << issues[1];
    EXPECT_NE(issues[2].find("twice"), std::string::npos) << issues[2];
    l.entries.resize(1);
    EXPECT_TRUE(sampling::validateSampleLayout(l, 4, 4).empty());
}

TEST(SampleLayoutCpu, PatternsSelectTheDocumentedPixels) {
    sampling::SamplePatternOptions o;
    o.pattern = sampling::SamplePattern::Checkerboard;
    EXPECT_EQ(sampling::buildSampleLayout(o, 6, 5).entries.size(), 15u);
    o.pattern = sampling::SamplePattern::EveryNth;
    o.n = 7;
    EXPECT_EQ(sampling::buildSampleLayout(o, 10, 10).entries.size(), 15u);  // ceil(100 / 7)
    o.pattern = sampling::SamplePattern::Random;
    o.fraction = 0.0f;
    EXPECT_TRUE(sampling::buildSampleLayout(o, 8, 8).entries.empty());
    o.fraction = 1.0f;
    EXPECT_EQ(sampling::buildSampleLayout(o, 8, 8).entries.size(), 64u);
}

// --- GPU: the SampleList pass -------------------------------------------------------------------

constexpr uint32_t kW = 40, kH = 24;  // not square, not a multiple of the 256-thread chunking

class SampleListTest : public GpuTest {
protected:
    static void SetUpTestSuite() { registerBuiltinPasses(); }

    static std::unique_ptr<RenderGraph> makeGraph(const std::string& params) {
        // The layout buffer itself is the marked output (no consumer needed).
        const std::string text =
            R"({ "version": 1, "name": "sample_list_test", "passes": [ { "name": "list", )"
            R"("type": "SampleList", "params": )" +
            params + R"( } ], "outputs": [ "list.layout" ] })";
        CompileOptions o;
        o.width = kW;
        o.height = kH;
        auto g = std::make_unique<RenderGraph>(ctx(), passRegistry());
        g->build(parseGraphText(text, "sample_list_test"), o);
        return g;
    }

    static SampleLayout layout(const RenderGraph& g) {
        return SampleLayout::parse(
            g.bufferFor(g.plan().findNode("list"), sampling::kSampleLayoutField).download(ctx()));
    }

    static uint32_t header(const RenderGraph& g, int word) {
        auto bytes =
            g.bufferFor(g.plan().findNode("list"), sampling::kSampleLayoutField).download(ctx());
        uint32_t v;
        std::memcpy(&v, bytes.data() + 4 * word, 4);
        return v;
    }

    // Runs one frame and checks the GPU list against the CPU builder with the pass's options.
    static SampleLayout runAndCompare(RenderGraph& g, sampling::SamplePatternOptions expected) {
        g.runFrame();
        SampleLayout got = layout(g);
        const SampleLayout want = sampling::buildSampleLayout(expected, kW, kH);
        EXPECT_EQ(got.entries.size(), want.entries.size());
        for (size_t i = 0; i < std::min(got.entries.size(), want.entries.size()); ++i) {
            EXPECT_EQ(got.entries[i].pixel, want.entries[i].pixel) << "entry " << i;
            EXPECT_EQ(got.entries[i].samples, want.entries[i].samples) << "entry " << i;
        }
        EXPECT_TRUE(sampling::validateSampleLayout(got, kW, kH).empty());
        return got;
    }
};

TEST_F(SampleListTest, AllListsEveryPixelRowMajorWithItsSpp) {
    auto g = makeGraph(R"({ "pattern": "all", "spp": 3 })");
    sampling::SamplePatternOptions o;
    o.samples = 3;
    const SampleLayout l = runAndCompare(*g, o);
    ASSERT_EQ(l.entries.size(), size_t(kW) * kH);
    EXPECT_EQ(sampling::unpackSamplePixel(l.entries[kW + 1].pixel), glm::uvec2(1, 1));
    EXPECT_EQ(l.totalSamples(), 3u * kW * kH);
    EXPECT_EQ(header(*g, 1), 3u) << "maxSamples";
}

TEST_F(SampleListTest, CheckerboardAndEveryNthGiveExpectedCounts) {
    auto g = makeGraph(R"({ "pattern": "checkerboard" })");
    sampling::SamplePatternOptions o;
    o.pattern = sampling::SamplePattern::Checkerboard;
    const SampleLayout l = runAndCompare(*g, o);
    EXPECT_EQ(l.entries.size(), size_t(kW) * kH / 2);
    for (const auto& e : l.entries) {
        glm::uvec2 p = sampling::unpackSamplePixel(e.pixel);
        EXPECT_EQ((p.x + p.y) % 2, 0u);
    }

    auto nth = makeGraph(R"({ "pattern": "every_nth", "n": 7 })");
    o.pattern = sampling::SamplePattern::EveryNth;
    o.n = 7;
    EXPECT_EQ(runAndCompare(*nth, o).entries.size(), (size_t(kW) * kH + 6) / 7);
}

TEST_F(SampleListTest, RandomIsDeterministicPerSeedAndAnimatesOnlyWhenAsked) {
    auto a = makeGraph(R"({ "pattern": "random", "fraction": 0.3, "seed": 5 })");
    auto b = makeGraph(R"({ "pattern": "random", "fraction": 0.3, "seed": 5 })");
    auto c = makeGraph(R"({ "pattern": "random", "fraction": 0.3, "seed": 6 })");
    sampling::SamplePatternOptions o;
    o.pattern = sampling::SamplePattern::Random;
    o.fraction = 0.3f;
    a->runFrame();
    b->runFrame();
    c->runFrame();
    const SampleLayout la = layout(*a), lb = layout(*b), lc = layout(*c);
    ASSERT_EQ(la.entries.size(), lb.entries.size());
    EXPECT_EQ(std::memcmp(la.entries.data(), lb.entries.data(), la.entries.size() * 8), 0);
    EXPECT_NE(la.bytes(), lc.bytes()) << "another seed, another selection";
    // About 30% of 960 pixels (binomial sd ~14): a broken threshold would be far off.
    EXPECT_GT(la.entries.size(), 220u);
    EXPECT_LT(la.entries.size(), 360u);
    EXPECT_TRUE(sampling::validateSampleLayout(la, kW, kH).empty());

    // Not animated: the same list next frame (and the pass is served from the cache).
    a->runFrame();
    EXPECT_EQ(layout(*a).bytes(), la.bytes());
    EXPECT_EQ(a->records()[a->plan().findNode("list")].status, PassStatus::Cached);

    auto anim = makeGraph(R"({ "pattern": "random", "fraction": 0.3, "animate": true })");
    anim->runFrame();
    const SampleLayout f0 = layout(*anim);
    anim->runFrame();
    EXPECT_NE(layout(*anim).bytes(), f0.bytes()) << "animated: a new selection every frame";
}

TEST_F(SampleListTest, RandomMatchesTheCpuBuilderBitForBit) {
    auto g = makeGraph(R"({ "pattern": "random", "fraction": 0.5, "seed": 11, "spp": 2 })");
    g->setSeed(1234);
    sampling::SamplePatternOptions o;
    o.pattern = sampling::SamplePattern::Random;
    o.fraction = 0.5f;
    o.samples = 2;
    // The pass's seed rule (SampleListPass::options): run seed mixed with the pass seed.
    o.seed = sampling::sampleListSeed(1234ull + 11ull * 0x9E3779B97F4A7C15ull, 0, false);
    runAndCompare(*g, o);
}

// The layout buffer follows the render size (16-byte header + 8 bytes per pixel): no capacity
// parameter to get wrong, at any size.
TEST_F(SampleListTest, LayoutBufferFollowsTheRenderSize) {
    auto g = makeGraph(R"({ "pattern": "all" })");
    const auto& plan = g->plan();
    const auto& r = plan.resources[plan.resourceOf.at({plan.findNode("list"), "layout"})];
    EXPECT_EQ(r.bufferBytes, 16u + 8u * kW * kH);
}

}  // namespace
