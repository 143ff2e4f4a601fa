// Layer-restricted à-trous (seed 000 §3.4, Algorithm 1: each iteration of a layer reconstructs
// only that layer's area): ATrousNH with `dispatch: tiles` runs each level only over the 8x8 tiles
// that need it. Tests: the ping-pong rule of ATrousNHPass::levelTileKeys keeps every pixel valid
// (CPU simulation over all schedules); the tile path's output is bit-identical to the full-screen
// path for 1-3 layers, mono and stereo, with and without hole filling; the GPU tile lists equal a
// CPU count of the tiles holding each layer set; and the lists are rebuilt when the gaze moves,
// not otherwise (the pass's tile_list_builds counter), with outputs still equal to the full path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/scene/BuiltinScenes.h"
#include "core/scene/Camera.h"
#include "core/scene/SceneGpu.h"
#include "core/vk/Resources.h"
#include "passes/ATrousNH/ATrousNHPass.h"
#include "passes/RegisterPasses.h"
#include "tests/graph/ATrousTestInputs.h"
#include "tests/passes/FeedPass.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::graph;
using fovea::passes::ATrousDispatch;
using fovea::passes::ATrousNHPass;
using fovea::passes::ATrousScheduleOptions;
using fovea::passes::buildATrousSchedule;

namespace {

constexpr int kTile = 8;

using TileInputs = test::ATrousInputs;

const PassRegistry& feedRegistry() {
    return test::atrousFeedRegistry();
}

// Concentric layers (radii 0.15 / 0.3 of the height) around an off-centre point per eye, so
// tiles hold one, two or three layers; sparse middle and outer sampling (holes to fill).
TileInputs randomTileInputs(int width, int height, int eyes, uint32_t seed) {
    return test::layeredATrousInputs(width, height, eyes, {0.4f, 0.45f, 0.15f, 0.3f, 0.7f, 0.3f},
                                     seed);
}

class ATrousTileTest : public GpuTest {
protected:
    struct Result {
        std::vector<float> denoised;
        std::string variant;
        std::vector<uint32_t> tiles;  // the atrous_tiles block
        uint32_t tileCount = 0;
    };

    // Feed -> ATrousNH (all inputs connected) with `params`, one frame.
    static Result run(const TileInputs& in, const std::string& params) {
        auto g = test::buildFeedGraph(ctx(), feedRegistry(), "ATrousNH", "dn", params,
                                      {"color", "normal", "position", "mask"}, {"denoised"},
                                      in.width, in.height);
        auto target = [&](const char* name) -> gpu::Image& {
            return const_cast<gpu::Image&>(g->image(name));
        };
        target("feed.color").uploadRGBA32F(ctx(), in.color);
        target("feed.normal").uploadRGBA32F(ctx(), in.normal);
        target("feed.position").uploadRGBA32F(ctx(), in.position);
        target("feed.mask").upload(ctx(), in.mask.data(), in.mask.size() * sizeof(uint32_t));
        g->runFrame();
        Result r;
        r.denoised = g->image("dn.denoised").downloadRGBA32F(ctx());
        const auto* pass =
            dynamic_cast<const ATrousNHPass*>(g->plan().nodes[g->plan().findNode("dn")].pass.get());
        r.variant = pass->variant();
        r.tiles = g->buffer("dn.tiles").downloadAs<uint32_t>(ctx());
        r.tileCount = pass->tileCount();
        return r;
    }
};

std::string withDispatch(const std::string& params, const char* dispatch) {
    return "{ " + params + (params.empty() ? "" : ", ") + R"("dispatch": ")" + dispatch + "\" }";
}

// Exact equality (memcmp), with the first differing value for the message.
::testing::AssertionResult identical(const std::vector<float>& got,
                                     const std::vector<float>& want) {
    if (got.size() != want.size())
        return ::testing::AssertionFailure() << got.size() << " vs " << want.size() << " floats";
    for (size_t i = 0; i < got.size(); ++i)
        if (std::memcmp(&got[i], &want[i], sizeof(float)) != 0)
            return ::testing::AssertionFailure() << "pixel " << i / 4 << " channel " << i % 4
                                                 << ": " << got[i] << " vs " << want[i];
    return ::testing::AssertionSuccess();
}

}  // namespace

// --- the ping-pong rule (CPU) -------------------------------------------------------------------

// Simulates every pixel class (layer l in a tile holding layer set c) through the levels exactly
// as ATrousNHPass::execute records them: level 0 full screen writing unchanged pixels to both
// images, level i over the tiles of key_i (0 = all), ping-pong ping <-> denoised ending in
// denoised. Checks, for every schedule shape: before each level the source image holds every
// pixel's current state (a tap may read any pixel), every pixel a level filters is in its tiles,
// the result ends in `denoised`, and a level that counts holes for the fill sees every pixel.
TEST(ATrousTileSchedule, LevelKeysKeepEveryPixelCurrentInTheSourceImage) {
    int checked = 0;
    for (int layers = 1; layers <= 3; ++layers)
        for (bool perLayer : {false, true})
            for (bool decreasing : {false, true})
                for (bool fill : {false, true})
                    for (int m = 0; m <= 3; ++m)
                        for (int n = 0; n <= 4; ++n)
                            for (int p = 0; p <= 5; ++p) {
                                ATrousScheduleOptions o;
                                o.layerCount = layers;
                                o.iterations[0] = m;
                                o.iterations[1] = n;
                                o.iterations[2] = p;
                                o.perLayer = perLayer;
                                o.decreasing = decreasing;
                                o.fill = fill;
                                o.fillReach = 20;
                                const auto s = buildATrousSchedule(o);
                                const auto keys = ATrousNHPass::levelTileKeys(s, layers, true);
                                size_t main = 0;
                                while (main < s.size() && !s[main].fill) ++main;
                                ASSERT_EQ(keys.size(), main);
                                const bool anyFill = main < s.size();
                                const std::string what =
                                    "layers " + std::to_string(layers) + " iterations " +
                                    std::to_string(m) + "/" + std::to_string(n) + "/" +
                                    std::to_string(p) + (perLayer ? " perLayer" : "") +
                                    (decreasing ? " decreasing" : "") + (fill ? " fill" : "");
                                if (main == 0) continue;
                                // Level 0 and a hole-counting last level are full screen.
                                EXPECT_EQ(keys[0], 0u) << what;
                                if (anyFill) {
                                    EXPECT_EQ(keys[main - 1], 0u) << what;
                                }
                                for (uint32_t c = 1; c < (1u << layers); ++c)
                                    for (int l = 0; l < layers; ++l) {
                                        if (!((c >> l) & 1u)) continue;
                                        // Versions: 0 = input state, k = after level k - 1;
                                        // -1 = garbage. Images: 0 = input, 1 = ping, 2 = den.
                                        int cur = 0, img[3] = {0, -1, -1};
                                        int src = 0;
                                        for (size_t i = 0; i < main; ++i) {
                                            const int dst = (main - 1 - i) % 2 == 0 ? 2 : 1;
                                            ASSERT_EQ(img[src], cur) << what << " level " << i;
                                            const bool active = (s[i].layers >> l) & 1u;
                                            const bool runs = keys[i] == 0 || (c & keys[i]) != 0;
                                            if (active) {
                                                ASSERT_TRUE(runs) << what << " level " << i;
                                            }
                                            if (runs) {
                                                if (active) cur = int(i) + 1;
                                                img[dst] = cur;
                                                if (i == 0 && main > 1 && !active)
                                                    img[dst == 1 ? 2 : 1] = cur;  // alsoDst
                                            }
                                            src = dst;
                                        }
                                        ASSERT_EQ(img[2], cur) << what << " result";
                                        ++checked;
                                    }
                            }
    EXPECT_GT(checked, 1000);
    // Without tiles every level is full screen (the Base / mono path is unchanged).
    ATrousScheduleOptions o;
    o.layerCount = 3;
    o.iterations[0] = 2;
    o.iterations[1] = 3;
    o.iterations[2] = 4;
    for (uint32_t k : ATrousNHPass::levelTileKeys(buildATrousSchedule(o), 3, false))
        EXPECT_EQ(k, 0u);
}

// --- tiles vs full screen (GPU) -----------------------------------------------------------------

// Bit-identical outputs, 1-3 layers, mono and stereo, fill on and off, both schedules and step
// orders; the tile path is taken exactly when a mask and >= 2 layers are there.
TEST_F(ATrousTileTest, TileDispatchEqualsFullScreenBitForBit) {
    struct Case {
        int width, height, eyes;
        std::string params;
    };
    const std::vector<Case> cases = {
        {64, 48, 1, R"("layers": 1, "iterations0": 3)"},
        {64, 48, 1, R"("layers": 2, "iterations0": 2, "iterations1": 4)"},
        {64, 48, 1, R"("layers": 3, "iterations0": 2, "iterations1": 3, "iterations2": 4)"},
        {64, 48, 1,
         R"("layers": 3, "iterations0": 1, "iterations1": 2, "iterations2": 3, "fill": false)"},
        {96, 40, 2, R"("layers": 1, "iterations0": 2, "fill": false)"},
        {96, 40, 2, R"("layers": 2, "iterations0": 1, "iterations1": 3, "fill": false)"},
        {96, 40, 2, R"("layers": 3, "iterations0": 2, "iterations1": 3, "iterations2": 4)"},
        {96, 40, 2,
         R"("layers": 3, "iterations0": 2, "iterations1": 1, "iterations2": 3, )"
         R"("schedule": "layers", "fill": false)"},
        {96, 40, 2,
         R"("layers": 3, "iterations0": 1, "iterations1": 2, "iterations2": 3, )"
         R"("schedule": "layers", "stepOrder": "increasing")"},
        {96, 40, 2,
         R"("layers": 3, "iterations0": 0, "iterations1": 2, "iterations2": 3, )"
         R"("stepOrder": "increasing", "fill": false)"},
    };
    for (size_t k = 0; k < cases.size(); ++k) {
        const Case& c = cases[k];
        const TileInputs in = randomTileInputs(c.width, c.height, c.eyes, 11u + uint32_t(k));
        const std::string eyes = R"("eyes": )" + std::to_string(c.eyes) + ", ";
        const Result tiles = run(in, withDispatch(eyes + c.params, "tiles"));
        const Result full = run(in, withDispatch(eyes + c.params, "full"));
        const bool layered = c.params.find(R"("layers": 1)") == std::string::npos;
        EXPECT_EQ(tiles.variant.find(",tiles") != std::string::npos, layered) << tiles.variant;
        EXPECT_EQ(full.variant.find(",tiles"), std::string::npos) << full.variant;
        EXPECT_TRUE(identical(tiles.denoised, full.denoised)) << "case " << k << ": " << c.params;
        // The inputs have holes: where hole filling is on, every pixel ends with a value.
        if (c.params.find("\"fill\": false") == std::string::npos) {
            for (size_t i = 0; i < tiles.denoised.size(); i += 4)
                ASSERT_EQ(tiles.denoised[i + 3], 1.0f) << "case " << k << " pixel " << i / 4;
        }
    }
}

// The lists the GPU built equal a CPU count of the tiles holding pixels of each layer set.
// Algorithm 1's literal schedule with 3 layers uses keys {0}, {0,1}, {1}, {1,2}, {2}.
TEST_F(ATrousTileTest, TileListsEqualTheTilesHoldingTheLayers) {
    const int w = 100, h = 44;  // not multiples of 8: partial tiles at the right and bottom
    const TileInputs in = randomTileInputs(w, h, 2, 5u);
    const Result r = run(in, withDispatch(R"("eyes": 2, "layers": 3, "iterations0": 2, )"
                                          R"("iterations1": 2, "iterations2": 3, )"
                                          R"("schedule": "layers", "fill": false)",
                                          "tiles"));
    const int tilesX = (w + kTile - 1) / kTile, tilesY = (h + kTile - 1) / kTile;
    ASSERT_EQ(r.tileCount, uint32_t(tilesX * tilesY));
    ASSERT_GE(r.tiles.size(), 32u + 8u * r.tileCount);
    std::vector<uint32_t> tileLayers(size_t(tilesX) * tilesY, 0u);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            tileLayers[size_t(y / kTile) * tilesX + x / kTile] |=
                1u << std::min((in.mask[size_t(y) * w + x] >> 1) & 3u, 2u);
    int restricted = 0;
    for (uint32_t key : {1u, 2u, 3u, 4u, 6u}) {
        std::set<std::pair<int, int>> want;
        for (int ty = 0; ty < tilesY; ++ty)
            for (int tx = 0; tx < tilesX; ++tx)
                if (tileLayers[size_t(ty) * tilesX + tx] & key) want.insert({tx, ty});
        const uint32_t count = r.tiles[key * 4 + 3];
        ASSERT_EQ(count, want.size()) << "key " << key;
        std::set<std::pair<int, int>> got;
        for (uint32_t i = 0; i < count; ++i) {
            const uint32_t t = r.tiles[32 + key * r.tileCount + i];
            got.insert({int(t & 0xffffu), int(t >> 16)});
        }
        EXPECT_EQ(got, want) << "key " << key;
        // The indirect command covers the list (x * y >= count, one row unless it overflows).
        EXPECT_EQ(r.tiles[key * 4 + 0], count) << "key " << key;
        EXPECT_EQ(r.tiles[key * 4 + 1], count > 0 ? 1u : 0u) << "key " << key;
        EXPECT_EQ(r.tiles[key * 4 + 2], 1u) << "key " << key;
        restricted += count < r.tileCount;
    }
    EXPECT_GE(restricted, 4) << "the layers should cover different tiles";
    // Keys the schedule does not use are not built.
    EXPECT_EQ(r.tiles[5 * 4 + 3], 0u);
    EXPECT_EQ(r.tiles[7 * 4 + 3], 0u);
}

// --- cached per gaze (GPU, FoveationMask -> ATrousNH) ------------------------------------------

class ATrousTileGazeTest : public GpuTest {
protected:
    static void SetUpTestSuite() { registerBuiltinPasses(); }

    static const PassRegistry& registry() {
        static PassRegistry r = [] {
            PassRegistry reg = passRegistry();
            reg.add({"Feed", "", [] {
                         return std::make_unique<test::FeedPass>(std::vector<test::FeedField>{
                             {"color", vk::Format::eR32G32B32A32Sfloat}});
                     }});
            return reg;
        }();
        return r;
    }
    // FoveationMask declares scene geometry (its cache key): a tiny scene.
    static const scene::Scene& plane() {
        static const scene::Scene s = scene::loadBuiltinScene("builtin:plane");
        return s;
    }
    static const scene::SceneGpu& planeGpu() {
        static const auto g = std::make_unique<scene::SceneGpu>(ctx(), plane());
        return *g;
    }
    static scene::FrameCamera camera(int width, int height, glm::vec2 left, glm::vec2 right) {
        scene::CameraRigOptions rig;
        rig.stereo = true;
        const glm::vec2 gaze[scene::kMaxEyes] = {left, right};
        const auto& s = plane();
        return scene::makeFrameCamera(s.cameras.empty() ? s.defaultCamera() : s.cameras.front(),
                                      uint32_t(width), uint32_t(height), rig, 0, nullptr, gaze);
    }
    static std::unique_ptr<RenderGraph> graph(int width, int height, const char* dispatch) {
        const std::string text =
            R"({ "version": 1, "name": "atrous_tiles_gaze", "passes": [ )"
            R"({ "name": "feed", "type": "Feed" }, )"
            R"({ "name": "mask", "type": "FoveationMask", "params": { "r0": 6, "r1": 12 } }, )"
            R"({ "name": "dn", "type": "ATrousNH", "params": { "layers": 3, "iterations0": 1, )"
            R"("iterations1": 2, "iterations2": 3, "dispatch": ")" +
            std::string(dispatch) +
            R"(" } } ], "edges": [ { "from": "feed.color", "to": "dn.color" }, )"
            R"({ "from": "mask.mask", "to": "dn.mask" } ], "outputs": [ "dn.denoised" ] })";
        CompileOptions o;
        o.width = uint32_t(width);
        o.height = uint32_t(height);
        o.sceneFeatures = planeGpu().features() | kSceneStereo;
        auto g = std::make_unique<RenderGraph>(ctx(), registry());
        g->setScene(&planeGpu());
        g->build(parseGraphText(text, "atrous_tiles_gaze"), o);
        return g;
    }
    static uint64_t builds(const RenderGraph& g) {
        return g.passStatistics(g.plan().findNode("dn")).value("tile_list_builds", uint64_t(0));
    }
};

// Seed 000 §3.2: the mask is fixed per gaze, so are the tile lists. Frames with an unchanged gaze
// reuse them (the counter stays), a gaze move rebuilds them once; every frame's output equals the
// full-screen path's (stale lists would differ: the layers moved).
TEST_F(ATrousTileGazeTest, ListsRebuiltWhenTheGazeMovesAndNotOtherwise) {
    constexpr int kW = 96, kH = 48;
    auto tiles = graph(kW, kH, "tiles");
    auto full = graph(kW, kH, "full");
    const TileInputs in = randomTileInputs(kW, kH, 2, 3u);
    for (auto* g : {tiles.get(), full.get()})
        const_cast<gpu::Image&>(g->image("feed.color")).uploadRGBA32F(ctx(), in.color);
    const glm::vec2 gazes[][2] = {{{0.5f, 0.5f}, {0.5f, 0.5f}},
                                  {{0.5f, 0.5f}, {0.5f, 0.5f}},
                                  {{0.5f, 0.5f}, {0.5f, 0.5f}},
                                  {{0.2f, 0.3f}, {0.7f, 0.6f}},
                                  {{0.2f, 0.3f}, {0.7f, 0.6f}}};
    const uint64_t wantBuilds[] = {1, 1, 1, 2, 2};
    std::vector<float> before;
    for (size_t f = 0; f < std::size(gazes); ++f) {
        for (auto* g : {tiles.get(), full.get()}) {
            g->setCamera(camera(kW, kH, gazes[f][0], gazes[f][1]));
            g->runFrame();
        }
        EXPECT_EQ(builds(*tiles), wantBuilds[f]) << "frame " << f;
        EXPECT_EQ(builds(*full), 0u) << "the full path builds no lists";
        const auto out = tiles->image("dn.denoised").downloadRGBA32F(ctx());
        EXPECT_TRUE(identical(out, full->image("dn.denoised").downloadRGBA32F(ctx())))
            << "frame " << f;
        if (f == 2) before = out;
        if (f == 3) {
            EXPECT_FALSE(identical(out, before)) << "the gaze move changed nothing";
        }
    }
    EXPECT_EQ(tiles->records()[tiles->plan().findNode("mask")].status, PassStatus::Cached);
}
