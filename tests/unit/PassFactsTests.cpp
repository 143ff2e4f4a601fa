// Pass::facts (core/graph/PassFacts.h): what evaluation reads about a pass comes from the pass's
// own parameters, so renaming a parameter the bench relies on, or changing its default, fails
// here rather than in a bench run. Also the readers built on it: the foveation radii of a graph
// (per-layer errors) and the samples per frame of a reference graph.
#include <gtest/gtest.h>

#include "core/graph/GraphDesc.h"
#include "core/graph/Param.h"
#include "core/graph/PassRegistry.h"
#include "core/util/Error.h"
#include "eval/reference/ReferenceErrors.h"
#include "eval/reference/ReferenceRender.h"
#include "passes/RegisterPasses.h"

using namespace fovea;

namespace {

graph::PassFacts factsOf(const std::string& type, const nlohmann::json& params) {
    registerBuiltinPasses();
    auto pass = graph::passRegistry().create(type, "p");
    graph::loadParams(*pass, params, "test.json", "/passes/0/params");
    return pass->facts();
}

graph::GraphDesc graphOf(const nlohmann::json& j) {
    return graph::parseGraphJson(j, "g.json");
}

}  // namespace

TEST(PassFacts, FoveationMaskReportsItsRadiiAndUnit) {
    const auto defaults = factsOf("FoveationMask", nlohmann::json::object());
    ASSERT_TRUE(defaults.foveationLayers);
    EXPECT_EQ(defaults.foveationLayers->r0, 144.0);  // the declared defaults, read once
    EXPECT_EQ(defaults.foveationLayers->r1, 288.0);
    EXPECT_FALSE(defaults.foveationLayers->degrees);
    const auto set = factsOf("FoveationMask", {{"r0", 5}, {"r1", 20}, {"radiusUnit", "degrees"}});
    ASSERT_TRUE(set.foveationLayers);
    EXPECT_EQ(set.foveationLayers->r0, 5.0);
    EXPECT_EQ(set.foveationLayers->r1, 20.0);
    EXPECT_TRUE(set.foveationLayers->degrees);
    EXPECT_FALSE(set.samplesPerFrame);
}

TEST(PassFacts, PathTraceReportsItsSamplesPerFrame) {
    EXPECT_EQ(factsOf("PathTrace", nlohmann::json::object()).samplesPerFrame, 1u);
    EXPECT_EQ(factsOf("PathTrace", {{"spp", 4}}).samplesPerFrame, 4u);
    EXPECT_FALSE(factsOf("PathTrace", {{"spp", 4}}).foveationLayers);
    EXPECT_FALSE(factsOf("Tonemap", nlohmann::json::object()).samplesPerFrame);
}

TEST(PassFacts, GraphReadersUseTheFacts) {
    registerBuiltinPasses();
    const graph::GraphDesc peres = graphOf(
        {{"version", 1},
         {"passes",
          {{{"name", "off"},
            {"type", "FoveationMask"},
            {"enabled", false},
            {"params", {{"r0", 1}}}},
           {{"name", "fm"}, {"type", "FoveationMask"}, {"params", {{"r0", 30}, {"r1", 60}}}}}},
         {"outputs", nlohmann::json::array({"fm.mask"})}});
    const auto radii = eval::foveationRadiiOf(peres);
    ASSERT_TRUE(radii);
    EXPECT_EQ(radii->r0, 30.0);  // the disabled pass is skipped
    EXPECT_EQ(radii->r1, 60.0);

    const graph::GraphDesc reference =
        graphOf({{"version", 1},
                 {"passes", {{{"name", "pt"}, {"type", "PathTrace"}, {"params", {{"spp", 8}}}}}},
                 {"outputs", nlohmann::json::array({"pt.radiance"})}});
    EXPECT_EQ(eval::referenceSamplesPerFrame(reference, "g.json"), 8u);
    EXPECT_EQ(eval::referenceFrames(1024, 8), 128u);
    const graph::GraphDesc none =
        graphOf({{"version", 1},
                 {"passes", {{{"name", "fm"}, {"type", "FoveationMask"}}}},
                 {"outputs", nlohmann::json::array({"fm.mask"})}});
    EXPECT_THROW(eval::referenceSamplesPerFrame(none, "g.json"), InputError);
    EXPECT_FALSE(eval::foveationRadiiOf(reference));
    // An unknown type is left to the compiler (its error names the pointer), not thrown here.
    const graph::GraphDesc typo = graphOf(
        {{"version", 1},
         {"passes",
          {{{"name", "x"}, {"type", "ImageSorce"}}, {{"name", "fm"}, {"type", "FoveationMask"}}}},
         {"outputs", nlohmann::json::array({"fm.mask"})}});
    EXPECT_EQ(eval::foveationRadiiOf(typo)->r0, 144.0);
}
