// Compile stages 1-5 (core/graph/CompilePasses, CompileEdges, CompileCullOrder): culling with
// reasons, edge checks with file and pointer, deterministic order. CPU only.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "tests/unit/CompilerTestUtil.h"

using namespace fovea;
using namespace fovea::graph;
using namespace fovea::compilertest;

// --- culling -------------------------------------------------------------------------------------

TEST(CompilerCull, UnreachablePassIsCulled) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "Src" }, { "name": "x", "type": "Filter" },
                  { "name": "f", "type": "Filter" } ],
      "edges": [ { "from": "src.color", "to": "x.in" }, { "from": "src.color", "to": "f.in" } ],
      "outputs": [ "f.out" ] })");
    EXPECT_EQ(aliveNames(plan), (Names{"src", "f"}));
    EXPECT_EQ(culled(plan), (Reasons{{"x", "reaches no marked output"}}));
    EXPECT_EQ(orderNames(plan), (Names{"src", "f"}));
    EXPECT_EQ(plan.positionOf(plan.findNode("x")), -1);
    // Later stages see neither the culled pass's edges nor its resources.
    EXPECT_EQ(plan.inputs.count({plan.findNode("x"), "in"}), 0u);
    EXPECT_FALSE(hasResource(plan, "x.out"));
    EXPECT_EQ(plan.resources.size(), 2u);
}

TEST(CompilerCull, DisabledPassPropagatesToRequiredConsumers) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "Src" }, { "name": "x", "type": "Filter", "enabled": false },
                  { "name": "y", "type": "Filter" }, { "name": "z", "type": "Filter" },
                  { "name": "keep", "type": "Filter" } ],
      "edges": [ { "from": "src.color", "to": "x.in" }, { "from": "x.out", "to": "y.in" },
                 { "from": "y.out", "to": "z.in" }, { "from": "src.color", "to": "keep.in" } ],
      "outputs": [ "z.out", "keep.out" ] })");
    EXPECT_EQ(aliveNames(plan), (Names{"src", "keep"}));
    EXPECT_EQ(culled(plan), (Reasons{{"x", "disabled in the graph file (\"enabled\": false)"},
                                     {"y", "input 'in' comes from culled pass 'x'"},
                                     {"z", "input 'in' comes from culled pass 'y'"}}));
    EXPECT_EQ(orderNames(plan), (Names{"src", "keep"}));
}

TEST(CompilerCull, DisabledPassMayLackRequiredInputs) {
    // A disabled pass is not checked for required inputs: it never runs.
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "Src" }, { "name": "off", "type": "Filter", "enabled": false },
                  { "name": "f", "type": "Filter" } ],
      "edges": [ { "from": "src.color", "to": "f.in" } ],
      "outputs": [ "f.out" ] })");
    EXPECT_EQ(aliveNames(plan), (Names{"src", "f"}));
    EXPECT_EQ(culled(plan).at("off"), "disabled in the graph file (\"enabled\": false)");
}

namespace {

const char* kSceneGraph = R"({ "version": 1,
  "passes": [ { "name": "src", "type": "Src" }, { "name": "ns", "type": "NeedsScene" },
              { "name": "f", "type": "Filter" }, { "name": "j", "type": "Join" } ],
  "edges": [ { "from": "ns.color", "to": "f.in" }, { "from": "src.color", "to": "j.a" },
             { "from": "ns.color", "to": "j.b" } ],
  "outputs": [ "f.out", "j.out" ] })";

}  // namespace

TEST(CompilerCull, SceneNeedsUnmet) {
    CompiledPlan plan = compile(kSceneGraph);
    EXPECT_EQ(aliveNames(plan), (Names{"src", "j"}));
    EXPECT_EQ(culled(plan), (Reasons{{"ns", "the scene lacks geometry, emissive"},
                                     {"f", "input 'in' comes from culled pass 'ns'"}}));
    // j's optional input from the culled pass is disconnected; j stays alive and keeps `a`.
    size_t j = plan.findNode("j");
    EXPECT_EQ(plan.inputs.count({j, "b"}), 0u);
    ASSERT_EQ(plan.inputs.count({j, "a"}), 1u);
    EXPECT_EQ(plan.inputs.at({j, "a"}).node, plan.findNode("src"));
    EXPECT_EQ(orderNames(plan), (Names{"src", "j"}));
    EXPECT_EQ(resource(plan, "j.out").width, 64u);
}

TEST(CompilerCull, SceneNeedsPartlyMet) {
    CompileOptions o = options64();
    o.sceneFeatures = kSceneGeometry | kSceneTextures;
    CompiledPlan plan = compile(kSceneGraph, o);
    EXPECT_EQ(culled(plan).at("ns"), "the scene lacks emissive");

    o.sceneFeatures = kSceneGeometry | kSceneEmissive;
    plan = compile(kSceneGraph, o);
    EXPECT_EQ(aliveNames(plan), (Names{"src", "ns", "f", "j"}));
    EXPECT_TRUE(culled(plan).empty());
    EXPECT_EQ(plan.inputs.count({plan.findNode("j"), "b"}), 1u);
}

TEST(CompilerCull, OptionalInputFromDisabledPassIsDisconnected) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "Src" }, { "name": "x", "type": "Src", "enabled": false },
                  { "name": "j", "type": "Join" } ],
      "edges": [ { "from": "src.color", "to": "j.a" }, { "from": "x.color", "to": "j.b" } ],
      "outputs": [ "j.out" ] })");
    EXPECT_EQ(aliveNames(plan), (Names{"src", "j"}));
    EXPECT_EQ(plan.inputs.count({plan.findNode("j"), "b"}), 0u);
    EXPECT_EQ(plan.inputs.size(), 1u);
    EXPECT_FALSE(hasResource(plan, "x.color"));
}

TEST(CompilerCull, OrderOnlyEdgesKeepNothingAlive) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "lonely", "type": "Src" }, { "name": "src", "type": "Src" },
                  { "name": "f", "type": "Filter" } ],
      "edges": [ { "from": "src.color", "to": "f.in" } ],
      "order": [ { "before": "lonely", "after": "f" } ],
      "outputs": [ "f.out" ] })");
    EXPECT_EQ(culled(plan), (Reasons{{"lonely", "reaches no marked output"}}));
    EXPECT_EQ(orderNames(plan), (Names{"src", "f"}));
}

TEST(CompilerCull, DelayedEdgeKeepsProducerAlive) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "Src" }, { "name": "j", "type": "Join" },
                  { "name": "p", "type": "Filter" } ],
      "edges": [ { "from": "src.color", "to": "j.a" }, { "from": "p.out", "to": "j.b", "delay": 1 },
                 { "from": "src.color", "to": "p.in" } ],
      "outputs": [ "j.out" ] })");
    EXPECT_EQ(aliveNames(plan), (Names{"src", "j", "p"}));
    EXPECT_EQ(resource(plan, "p.out").lifetime, Lifetime::History);
}

TEST(CompilerCull, EveryOutputCulledIsAnError) {
    std::string msg = compileError(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "Src" }, { "name": "x", "type": "Filter", "enabled": false },
                  { "name": "ns", "type": "NeedsScene" } ],
      "edges": [ { "from": "src.color", "to": "x.in" } ],
      "outputs": [ "x.out", "ns.color" ] })");
    EXPECT_EQ(msg,
              "test.json: /outputs: every marked output was culled (x: disabled in the graph file "
              "(\"enabled\": false); ns: the scene lacks geometry, emissive)");
}

// --- edge checks
// ----------------------------------------------------------------------------------

TEST(CompilerCheck, ErrorsNameFilePointerAndProblem) {
    struct Case {
        const char* graph;
        const char* expected;
    };
    const Case cases[] = {
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" }, { "name": "f", "type": "Filtre" } ],
              "edges": [ { "from": "s.color", "to": "f.in" } ], "outputs": [ "f.out" ] })",
         "test.json: /passes/1/type: unknown pass type 'Filtre' (did you mean 'Filter'?)"},
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" }, { "name": "f", "type": "Filter" } ],
              "edges": [ { "from": "s.colr", "to": "f.in" } ], "outputs": [ "f.out" ] })",
         "test.json: /edges/0/from: pass 's' (Src) has no output 'colr' (did you mean 'color'?) "
         "(outputs: color)"},
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" }, { "name": "f", "type": "Filter" } ],
              "edges": [ { "from": "s.color", "to": "f.inn" } ], "outputs": [ "f.out" ] })",
         "test.json: /edges/0/to: pass 'f' (Filter) has no input 'inn' (did you mean 'in'?)"},
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" }, { "name": "f", "type": "Filter" } ],
              "edges": [ { "from": "s.color", "to": "f.out" } ], "outputs": [ "f.out" ] })",
         "test.json: /edges/0/to: edge direction wrong: 'f.out' is an output"},
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" }, { "name": "x", "type": "Internal" },
                                         { "name": "f", "type": "Filter" } ],
              "edges": [ { "from": "s.color", "to": "x.in" }, { "from": "x.scratch", "to": "f.in" } ],
              "outputs": [ "f.out" ] })",
         "test.json: /edges/1/from: 'x.scratch' is internal to pass 'x' and cannot be connected"},
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" }, { "name": "f", "type": "Filter" } ],
              "edges": [ ], "outputs": [ "f.out" ] })",
         "test.json: /passes/1: missing required input: 'f.in' has no edge"},
        {R"({ "version": 1, "passes": [ { "name": "l", "type": "LdrSrc" }, { "name": "f", "type": "Filter" } ],
              "edges": [ { "from": "l.ldr", "to": "f.in" } ], "outputs": [ "f.out" ] })",
         "test.json: /edges/0: format mismatch: 'l.ldr' is rgba8 but 'f.in' expects rgba32f"},
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" }, { "name": "bc", "type": "BufferConsumer" } ],
              "edges": [ { "from": "s.color", "to": "bc.buf" } ], "outputs": [ "bc.color" ] })",
         "test.json: /edges/0: kind mismatch: 's.color' is an image but 'bc.buf' expects a buffer"},
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" }, { "name": "f", "type": "Filter" } ],
              "edges": [ { "from": "s.color", "to": "f.in" } ], "outputs": [ "f.in" ] })",
         "test.json: /outputs/0: edge direction wrong: 'f.in' is an input"},
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" } ], "outputs": [ "s.colour" ] })",
         "test.json: /outputs/0: pass 's' (Src) has no output 'colour' (did you mean 'color'?)"},
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" } ] })",
         "test.json: /outputs: the graph marks no outputs; nothing would be run"},
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" },
                                         { "name": "f", "type": "Filter", "params": { "strength": 11 } } ],
              "edges": [ { "from": "s.color", "to": "f.in" } ], "outputs": [ "f.out" ] })",
         "test.json: /passes/1/params/strength: out of range: 11 (allowed 0..10)"},
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" },
                                         { "name": "f", "type": "Filter", "params": { "strenght": 1 } } ],
              "edges": [ { "from": "s.color", "to": "f.in" } ], "outputs": [ "f.out" ] })",
         "test.json: /passes/1/params/strenght: unknown parameter 'strenght' (did you mean "
         "'strength'?)"},
        // Cycles: through data edges, and through an order edge.
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" }, { "name": "x", "type": "Join" },
                                         { "name": "y", "type": "Filter" } ],
              "edges": [ { "from": "s.color", "to": "x.a" }, { "from": "y.out", "to": "x.b" },
                         { "from": "x.out", "to": "y.in" } ], "outputs": [ "y.out" ] })",
         "test.json: /edges/1: cycle without delay: x -> y -> x"},
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" }, { "name": "f", "type": "Filter" } ],
              "edges": [ { "from": "s.color", "to": "f.in" } ],
              "order": [ { "before": "f", "after": "s" } ], "outputs": [ "f.out" ] })",
         "test.json: /order/0: cycle without delay: s -> f -> s"},
        {R"({ "version": 1, "passes": [ { "name": "s", "type": "Src" }, { "name": "j", "type": "Join" } ],
              "edges": [ { "from": "s.color", "to": "j.a" }, { "from": "j.out", "to": "j.b" } ],
              "outputs": [ "j.out" ] })",
         "test.json: /edges/1: cycle without delay: j -> j"},
    };
    for (const Case& c : cases) {
        std::string msg = compileError(c.graph);
        EXPECT_NE(msg.find(c.expected), std::string::npos)
            << "expected: " << c.expected << "\n     got: " << msg;
    }
}

TEST(CompilerCheck, AnyFormatInputAcceptsEveryFormat) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "l", "type": "LdrSrc" }, { "name": "j", "type": "Join" } ],
      "edges": [ { "from": "l.ldr", "to": "j.a" } ], "outputs": [ "j.out" ] })");
    EXPECT_EQ(orderNames(plan), (Names{"l", "j"}));
    EXPECT_EQ(resource(plan, "l.ldr").format, vk::Format::eR8G8B8A8Unorm);
    EXPECT_EQ(resource(plan, "l.ldr").bytes(), 64u * 64 * 4);
}

TEST(CompilerCheck, ParametersAreLoadedIntoThePasses) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "s", "type": "Src" },
                  { "name": "a", "type": "Filter", "params": { "strength": 2.5 } },
                  { "name": "b", "type": "Filter" } ],
      "edges": [ { "from": "s.color", "to": "a.in" }, { "from": "a.out", "to": "b.in" } ],
      "outputs": [ "b.out" ] })");
    auto strength = [&](const char* name) {
        return dynamic_cast<testpasses::Filter&>(*plan.nodes[plan.findNode(name)].pass).strength();
    };
    EXPECT_FLOAT_EQ(strength("a"), 2.5f);
    EXPECT_FLOAT_EQ(strength("b"), 1.0f);  // the declared default
    EXPECT_EQ(plan.nodes[plan.findNode("a")].pass->name(), "a");
    EXPECT_EQ(plan.nodes[plan.findNode("a")].pass->type(), "Filter");
    EXPECT_EQ(plan.nodes[plan.findNode("b")].pointer, "/passes/2");
}

TEST(CompilerCheck, StagesRunIndividually) {
    GraphDesc desc = parseGraphText(kChain, "test.json");
    CompiledPlan plan;
    plan.options = options64();
    instantiatePasses(desc, registry(), plan);
    ASSERT_EQ(plan.nodes.size(), 5u);
    EXPECT_EQ(plan.file, "test.json");
    reflectPasses(plan);
    EXPECT_NE(plan.nodes[1].reflection.find("in"), nullptr);
    checkEdges(desc, plan);
    EXPECT_EQ(plan.inputs.size(), 4u);
    EXPECT_EQ(plan.outputs, (std::vector<std::pair<size_t, std::string>>{{4, "out"}}));
    cullPasses(plan);
    orderPasses(plan);
    EXPECT_EQ(plan.order, (std::vector<size_t>{0, 1, 2, 3, 4}));
    resolveResources(plan);
    EXPECT_EQ(plan.resources.size(), 5u);
    EXPECT_EQ(plan.inputs.at({2, "in"}).resource, plan.resourceOf.at({1, "out"}));
    aliasResources(plan);
    EXPECT_EQ(plan.aliasGroups.size(), 2u);
}

// --- order
// ----------------------------------------------------------------------------------------

TEST(CompilerOrder, TiesFollowGraphFileOrder) {
    const char* graph = R"({ "version": 1,
      "passes": [ { "name": "j", "type": "Join" }, { "name": "%s", "type": "Src" },
                  { "name": "%s", "type": "Src" } ],
      "edges": [ { "from": "s1.color", "to": "j.a" }, { "from": "s2.color", "to": "j.b" } ],
      "outputs": [ "j.out" ] })";
    auto withNames = [&](const char* first, const char* second) {
        std::string text = graph;
        text.replace(text.find("%s"), 2, first);
        text.replace(text.find("%s"), 2, second);
        return text;
    };
    EXPECT_EQ(orderNames(compile(withNames("s1", "s2"))), (Names{"s1", "s2", "j"}));
    EXPECT_EQ(orderNames(compile(withNames("s2", "s1"))), (Names{"s2", "s1", "j"}));
}

TEST(CompilerOrder, ChainListedBackwardsRunsForwards) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "f3", "type": "Filter" }, { "name": "f2", "type": "Filter" },
                  { "name": "f1", "type": "Filter" }, { "name": "src", "type": "Src" } ],
      "edges": [ { "from": "src.color", "to": "f1.in" }, { "from": "f1.out", "to": "f2.in" },
                 { "from": "f2.out", "to": "f3.in" } ],
      "outputs": [ "f3.out" ] })");
    EXPECT_EQ(orderNames(plan), (Names{"src", "f1", "f2", "f3"}));
    EXPECT_EQ(plan.positionOf(plan.findNode("f3")), 3);
    EXPECT_EQ(plan.positionOf(plan.findNode("src")), 0);
}

TEST(CompilerOrder, OrderEdgesChangeTheOrder) {
    const char* base = R"({ "version": 1,
      "passes": [ { "name": "j", "type": "Join" }, { "name": "s1", "type": "Src" },
                  { "name": "s2", "type": "Src" } ],
      "edges": [ { "from": "s1.color", "to": "j.a" }, { "from": "s2.color", "to": "j.b" } ],
      %s
      "outputs": [ "j.out" ] })";
    auto withOrder = [&](const std::string& order) {
        std::string text = base;
        text.replace(text.find("%s"), 2, order);
        return text;
    };
    EXPECT_EQ(orderNames(compile(withOrder(""))), (Names{"s1", "s2", "j"}));
    CompiledPlan plan = compile(withOrder(R"("order": [ { "before": "s2", "after": "s1" } ],)"));
    EXPECT_EQ(orderNames(plan), (Names{"s2", "s1", "j"}));
    EXPECT_EQ(plan.orderEdges, (std::vector<std::pair<size_t, size_t>>{{2, 1}}));
}

TEST(CompilerOrder, OrderEdgeCanDelayAnIndependentPass) {
    // Without the order edge `other` runs first (file order); with it, after f.
    const char* base = R"({ "version": 1,
      "passes": [ { "name": "other", "type": "Src" }, { "name": "src", "type": "Src" },
                  { "name": "f", "type": "Filter" }, { "name": "j", "type": "Join" } ],
      "edges": [ { "from": "src.color", "to": "f.in" }, { "from": "f.out", "to": "j.a" },
                 { "from": "other.color", "to": "j.b" } ],
      %s "outputs": [ "j.out" ] })";
    std::string plain = base, ordered = base;
    plain.replace(plain.find("%s"), 2, "");
    ordered.replace(ordered.find("%s"), 2, R"("order": [ { "before": "f", "after": "other" } ],)");
    EXPECT_EQ(orderNames(compile(plain)), (Names{"other", "src", "f", "j"}));
    EXPECT_EQ(orderNames(compile(ordered)), (Names{"src", "f", "other", "j"}));
}

TEST(CompilerOrder, DelayedEdgeDoesNotConstrainOrder) {
    const char* base = R"({ "version": 1,
      "passes": [ { "name": "j", "type": "Join" }, { "name": "s", "type": "Src" },
                  { "name": "f", "type": "Filter" } ],
      "edges": [ { "from": "s.color", "to": "j.a" }, { "from": "f.out", "to": "j.b", "delay": %s },
                 { "from": "s.color", "to": "f.in" } ],
      "outputs": [ "j.out" ] })";
    auto withDelay = [&](const char* delay) {
        std::string text = base;
        text.replace(text.find("%s"), 2, delay);
        return text;
    };
    // j reads last frame's f.out, so it may run before f (and does: it comes first in the file).
    EXPECT_EQ(orderNames(compile(withDelay("1"))), (Names{"s", "j", "f"}));
    EXPECT_EQ(orderNames(compile(withDelay("0"))), (Names{"s", "f", "j"}));
}

TEST(CompilerOrder, SameGraphCompiledTwiceGivesTheSamePlan) {
    const char* graph = R"({ "version": 1,
      "passes": [ { "name": "z", "type": "Join" }, { "name": "c", "type": "Src" },
                  { "name": "b", "type": "Src" }, { "name": "a", "type": "Filter" },
                  { "name": "y", "type": "Join" } ],
      "edges": [ { "from": "c.color", "to": "a.in" }, { "from": "a.out", "to": "y.a" },
                 { "from": "b.color", "to": "y.b" }, { "from": "y.out", "to": "z.a" },
                 { "from": "z.out", "to": "z.b", "delay": 1 } ],
      "outputs": [ "z.out" ] })";
    CompiledPlan first = compile(graph), second = compile(graph);
    EXPECT_EQ(orderNames(first), (Names{"c", "b", "a", "y", "z"}));
    EXPECT_EQ(first.order, second.order);
    EXPECT_EQ(dumpPlanJson(first), dumpPlanJson(second));
    EXPECT_EQ(dumpPlanText(first), dumpPlanText(second));
}
