// RenderGraph::update (core/graph/RenderGraphUpdate.cpp): a parameter edit recompiles only the
// passes whose parameters changed, shares pipelines whose shader and defines did not change, keeps
// resources and cached results, and falls back to a full build when the plan's shape changes.
#include <gtest/gtest.h>

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

class RenderGraphUpdateTest : public test::GpuTest {};

constexpr const char* kGraph = R"({
  "version": 1,
  "passes": [
    { "name": "src", "type": "ImageSource", "params": { "pattern": "gradient" } },
    { "name": "tm", "type": "Tonemap" },
    { "name": "blit", "type": "Blit" }
  ],
  "edges": [ { "from": "src.color", "to": "tm.color" }, { "from": "src.color", "to": "blit.color" } ],
  "outputs": [ "tm.ldr", "blit.result" ]
})";

double meanOf(const std::vector<float>& px) {
    double sum = 0;
    for (float v : px) sum += v;
    return px.empty() ? 0.0 : sum / double(px.size());
}

TEST_F(RenderGraphUpdateTest, ParameterEditRecompilesOnlyTheChangedPass) {
    registerBuiltinPasses();
    RenderGraph g(ctx(), passRegistry());
    CompileOptions options;
    options.width = options.height = 32;
    GraphDesc desc = parseGraphText(kGraph, "update.json");
    g.build(desc, options);
    g.runFrame();
    const auto before = g.image("tm.ldr").downloadRGBA32F(ctx());
    const gpu::Image* blitImage = &g.image("blit.result");

    desc.passes[1].params["exposure"] = -4.0;
    const auto result = g.update(desc);
    EXPECT_TRUE(result.inPlace);
    EXPECT_EQ(result.recompiled, std::vector<std::string>{"tm"});
    EXPECT_EQ(result.pipelinesCreated, 0u) << "exposure only reaches push constants";
    EXPECT_EQ(result.pipelinesReused, 1u);
    EXPECT_EQ(&g.image("blit.result"), blitImage) << "resources are kept in place";
    EXPECT_EQ(g.desc(), desc);
    g.runFrame();
    // The source kept its instance and cache key: still cached; the tone mapper ran again.
    EXPECT_EQ(g.records()[0].status, PassStatus::Cached);
    EXPECT_EQ(g.records()[1].status, PassStatus::Executed);
    const auto after = g.image("tm.ldr").downloadRGBA32F(ctx());
    EXPECT_LT(meanOf(after), meanOf(before) * 0.7) << "four stops down must darken the output";

    // A bad value: an input error, and the running graph is untouched.
    GraphDesc bad = desc;
    bad.passes[1].params["exposure"] = "bright";
    EXPECT_THROW(g.update(bad), InputError);
    EXPECT_TRUE(g.built());
    EXPECT_EQ(g.desc(), desc);
    g.runFrame();

    // Blit's scale changes its output size: the plan's shape changes, so a full build.
    desc.passes[2].params["scale"] = 0.5;
    const auto full = g.update(desc);
    EXPECT_FALSE(full.inPlace);
    EXPECT_TRUE(full.recompiled.empty());
    EXPECT_EQ(g.image("blit.result").width(), 16u);
    EXPECT_GE(full.pipelinesReused, 3u) << "a param-driven rebuild still shares pipelines";
    g.runFrame();
}

TEST_F(RenderGraphUpdateTest, SharedPipelinesKeepTheirOwnBindings) {
    // Two passes of the same type share one compiled pipeline but bind their own fields: both
    // outputs are right (a shared staged state would give both the same image).
    registerBuiltinPasses();
    RenderGraph g(ctx(), passRegistry());
    CompileOptions options;
    options.width = options.height = 16;
    const GraphDesc desc = parseGraphText(R"({
      "version": 1,
      "passes": [
        { "name": "a", "type": "ImageSource", "params": { "pattern": "constant", "value": [0.25, 0.25, 0.25] } },
        { "name": "b", "type": "ImageSource", "params": { "pattern": "constant", "value": [0.75, 0.75, 0.75] } }
      ],
      "outputs": [ "a.color", "b.color" ]
    })",
                                          "two.json");
    g.build(desc, options);
    g.runFrame();
    EXPECT_FLOAT_EQ(g.image("a.color").downloadRGBA32F(ctx())[0], 0.25f);
    EXPECT_FLOAT_EQ(g.image("b.color").downloadRGBA32F(ctx())[0], 0.75f);
}

}  // namespace
