// GPU tests of the utility passes and of RenderGraph's build/submit robustness: Tonemap's rgba8
// output reaches a PNG byte-exact (no second sRGB encoding), RenderGraph submits frames under the
// context's queue lock, a build() that fails after the plan compiled leaves an unbuilt graph
// (runFrame throws a clear RuntimeError) that a later build() repairs, and the documented
// ImageSource/Combine numerics (seed formula, alpha of frame-index, alpha combined). Tiny images.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/image/ImageIO.h"
#include "core/util/Error.h"
#include "core/vk/Formats.h"
#include "core/vk/Resources.h"
#include "passes/ImageSource/ImageSourcePass.h"
#include "passes/RegisterPasses.h"
#include "tests/graph/GpuTestFixture.h"

namespace fs = std::filesystem;
using namespace fovea;
using namespace fovea::graph;

namespace {

CompileOptions sized(uint32_t width, uint32_t height) {
    CompileOptions o;
    o.width = width;
    o.height = height;
    return o;
}

class UtilityPassGpu : public GpuTest {
protected:
    static void SetUpTestSuite() { registerBuiltinPasses(); }

    static std::unique_ptr<RenderGraph> graphOf(const std::string& text, uint32_t w = 16,
                                                uint32_t h = 16) {
        auto g = std::make_unique<RenderGraph>(ctx(), passRegistry());
        g->build(parseGraphText(text, "test.json"), sized(w, h));
        return g;
    }

    static std::vector<float> pixels(const RenderGraph& g, const std::string& resource) {
        return g.image(resource).downloadRGBA32F(ctx());
    }
};

// ImageSource `name` with `params` as the only pass and output.
std::string sourceGraph(const std::string& params) {
    return R"({ "version": 1, "passes": [ { "name": "src", "type": "ImageSource", "params": )" +
           params + R"( } ], "outputs": [ "src.color" ] })";
}

// --- 1. PNG of an rgba8 output -------------------------------------------------------------

TEST_F(UtilityPassGpu, TonemapOutputReachesPngByteExact) {
    auto g = graphOf(R"({ "version": 1,
      "passes": [ { "name": "gradient", "type": "ImageSource",
                    "params": { "pattern": "gradient", "value": [4, 2, 1] } },
                  { "name": "tm", "type": "Tonemap", "params": { "operator": "aces" } } ],
      "edges": [ { "from": "gradient.color", "to": "tm.color" } ], "outputs": [ "tm.ldr" ] })");
    g->runFrame();
    const gpu::Image& ldr = g->image("tm.ldr");
    ASSERT_TRUE(gpu::formatIsUnorm8(ldr.format()));
    image::ImageRGBA img{ldr.width(), ldr.height(), ldr.downloadRGBA32F(ctx())};
    const fs::path png =
        fs::temp_directory_path() / ("fovea_utilfix_ldr_" + std::to_string(::getpid()) + ".png");
    // What `fovea run` does for an rgba8 output: the encoding follows the format.
    image::writePng(
        png, img,
        gpu::formatIsUnorm8(ldr.format()) ? image::PngEncoding::AsIs : image::PngEncoding::Srgb);
    // Read back as stored (8-bit k -> k/255, no colour conversion): the bytes in the file.
    const image::ImageRGBA back = image::readImage(png);
    ASSERT_EQ(back.pixels.size(), img.pixels.size());
    std::vector<uint8_t> bytes(back.pixels.size());
    for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = uint8_t(std::lround(back.pixels[i] * 255));
    fs::remove(png);
    size_t differ = 0, distinct = 0;
    for (size_t i = 0; i < bytes.size(); ++i) {
        long stored = std::lround(img.pixels[i] * 255.0f);  // the byte the GPU stored
        differ += bytes[i] != stored;
        distinct += i > 0 && bytes[i] != bytes[i - 1];
    }
    EXPECT_EQ(differ, 0u) << "PNG bytes differ from the stored rgba8 bytes";
    EXPECT_GT(distinct, 16u) << "the gradient should give many different bytes";
}

// --- 5. queue lock ------------------------------------------------------------------------------

TEST_F(UtilityPassGpu, FrameSubmitWaitsForTheContextQueueLock) {
    auto g = graphOf(sourceGraph(R"({ "pattern": "constant", "value": [3, 3, 3] })"));
    g->runFrame();  // warm
    std::atomic<bool> lockHeld{false};
    std::mutex m;
    std::condition_variable cv;
    bool frameDone = false;
    std::string frameError;
    std::thread frame([&] {
        while (!lockHeld) std::this_thread::yield();
        try {
            g->runFrame();
        } catch (const std::exception& e) {
            frameError = e.what();
        }
        {
            std::lock_guard lock(m);
            frameDone = true;
        }
        cv.notify_all();
    });
    bool finishedWhileLocked = false;
    // submitAndWait holds the queue lock while it records: a frame started meanwhile must not
    // reach the queue until it is released. (The bound only limits how long we look; with the
    // lock taken the frame cannot finish in any amount of time.)
    ctx().submitAndWait([&](const vk::raii::CommandBuffer&) {
        lockHeld = true;
        std::unique_lock lock(m);
        finishedWhileLocked = cv.wait_for(lock, std::chrono::seconds(1), [&] { return frameDone; });
    });
    frame.join();
    EXPECT_FALSE(finishedWhileLocked) << "runFrame submitted while another submit held the lock";
    EXPECT_TRUE(frameError.empty()) << frameError;
    EXPECT_EQ(g->frameIndex(), 2u);
    std::vector<float> px = pixels(*g, "src.color");
    ASSERT_EQ(px.size(), 16u * 16u * 4u);
    for (size_t i = 0; i < px.size(); ++i) ASSERT_EQ(px[i], i % 4 == 3 ? 1.0f : 3.0f) << i;
}

// --- 7. failed build ----------------------------------------------------------------------------

// Compiles like a pass whose shader does not compile: throws from compile().
class FailingCompilePass : public Pass {
public:
    void reflect(Reflection& r) const override {
        r.input("color", vk::Format::eR32G32B32A32Sfloat);
        r.output("out", vk::Format::eR32G32B32A32Sfloat).sameAs("color");
    }
    void compile(CompileContext&) override {
        throw RuntimeError("failing.comp: shader compile error (test)");
    }
    void execute(ExecuteContext&) override {}
};

const PassRegistry& failingRegistry() {
    static PassRegistry registry = [] {
        PassRegistry r;
        r.add({"ImageSource", "", [] { return std::make_unique<passes::ImageSourcePass>(); }});
        r.add({"Failing", "", [] { return std::make_unique<FailingCompilePass>(); }});
        return r;
    }();
    return registry;
}

TEST_F(UtilityPassGpu, RunFrameBeforeAnyBuildThrows) {
    RenderGraph g(ctx(), passRegistry());
    EXPECT_FALSE(g.built());
    try {
        g.runFrame();
        ADD_FAILURE() << "ran an unbuilt graph";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("not built"), std::string::npos) << e.what();
    }
}

TEST_F(UtilityPassGpu, FailedBuildLeavesAnUnbuiltGraphThatRebuilds) {
    const std::string good = sourceGraph(R"({ "pattern": "constant", "value": [2, 2, 2] })");
    const std::string failing = R"({ "version": 1,
      "passes": [ { "name": "src", "type": "ImageSource" }, { "name": "bad", "type": "Failing" } ],
      "edges": [ { "from": "src.color", "to": "bad.color" } ], "outputs": [ "bad.out" ] })";
    RenderGraph g(ctx(), failingRegistry());
    g.build(parseGraphText(good, "good.json"), sized(8, 8));
    g.runFrame();
    g.runFrame();
    ASSERT_TRUE(g.built());

    EXPECT_THROW(g.build(parseGraphText(failing, "failing.json"), sized(8, 8)), RuntimeError);
    EXPECT_FALSE(g.built());
    try {
        g.runFrame();
        ADD_FAILURE() << "ran a half-built graph";
    } catch (const RuntimeError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("not built"), std::string::npos) << what;
        EXPECT_NE(what.find("shader compile error (test)"), std::string::npos) << what;
    }
    EXPECT_THROW(g.image("src.color"), RuntimeError);
    EXPECT_THROW(g.image("bad.out"), RuntimeError);
    EXPECT_TRUE(g.plan().order.empty());
    g.reset();  // harmless on an unbuilt graph

    // A later build repairs it; history starts over.
    g.build(parseGraphText(good, "good.json"), sized(8, 8));
    EXPECT_TRUE(g.built());
    g.runFrame();
    EXPECT_EQ(g.framesSinceReset(), 1u);
    std::vector<float> px = g.image("src.color").downloadRGBA32F(ctx());
    ASSERT_EQ(px.size(), 8u * 8u * 4u);
    for (size_t i = 0; i < px.size(); ++i) ASSERT_EQ(px[i], i % 4 == 3 ? 1.0f : 2.0f) << i;
}

// --- 4. documented numerics -------------------------------------------------------------------

TEST_F(UtilityPassGpu, ImageSourceSeedIsSeedPlus7919TimesRunSeed) {
    auto noise = [&](uint32_t seedParam, uint64_t runSeed) {
        auto g = graphOf(
            sourceGraph(R"({ "pattern": "noise", "seed": )" + std::to_string(seedParam) + " }"));
        g->setSeed(runSeed);
        g->runFrame();
        return pixels(*g, "src.color");
    };
    const auto documented = noise(5, 3);
    EXPECT_EQ(documented, noise(5 + 7919 * 3, 0));
    EXPECT_NE(documented, noise(5 + 3, 0)) << "the run seed is not simply added";
}

TEST_F(UtilityPassGpu, FrameIndexAlphaAndCombineAlphaAreAsDocumented) {
    auto g = graphOf(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "ImageSource", "params": { "pattern": "frame-index" } },
                  { "name": "k", "type": "ImageSource",
                    "params": { "pattern": "constant", "value": [1, 1, 1] } },
                  { "name": "diff", "type": "Combine", "params": { "weightA": 1, "weightB": -1 } } ],
      "edges": [ { "from": "k.color", "to": "diff.a" }, { "from": "k.color", "to": "diff.b" } ],
      "outputs": [ "src.color", "diff.result" ] })",
                     4, 4);
    for (int f = 0; f < 3; ++f) g->runFrame();
    for (float v : pixels(*g, "src.color")) ASSERT_EQ(v, 2.0f) << "frame 2: (2, 2, 2, 2)";
    for (float v : pixels(*g, "diff.result")) ASSERT_EQ(v, 0.0f) << "alpha 1 - 1 = 0 too";
}

}  // namespace
