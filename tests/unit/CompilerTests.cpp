// The CPU compile stages of the render graph (core/graph/Compile*.cpp, PlanDump.cpp): culling
// with reasons, deterministic order, resource resolution, aliasing, barriers, history rings and
// the dumps. Graphs use the test pass types of TestPasses.h in a local registry; no GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "core/graph/CompilerStages.h"
#include "core/graph/GraphDesc.h"
#include "core/util/Error.h"
#include "tests/unit/TestPasses.h"

using namespace fovea;
using namespace fovea::graph;
using fovea::testpasses::kRgba32fBytes;

namespace {

const PassRegistry& registry() {
    static const PassRegistry r = testpasses::testRegistry();
    return r;
}

CompileOptions options64(bool aliasing = true) {
    CompileOptions o;
    o.width = 64;
    o.height = 64;
    o.aliasing = aliasing;
    return o;
}

CompiledPlan compile(const std::string& text, const CompileOptions& o = options64()) {
    return compileGraphPlan(parseGraphText(text, "test.json"), registry(), o);
}

// The message of the InputError compiling `text` throws, or "<no error>".
std::string compileError(const std::string& text, const CompileOptions& o = options64()) {
    try {
        compile(text, o);
    } catch (const InputError& e) {
        return e.what();
    }
    return "<no error>";
}

std::vector<std::string> orderNames(const CompiledPlan& plan) {
    std::vector<std::string> out;
    for (size_t n : plan.order) out.push_back(plan.nodes[n].name);
    return out;
}

std::vector<std::string> aliveNames(const CompiledPlan& plan) {
    std::vector<std::string> out;
    for (const auto& node : plan.nodes)
        if (node.alive) out.push_back(node.name);
    return out;
}

// Culled pass name -> reason.
std::map<std::string, std::string> culled(const CompiledPlan& plan) {
    std::map<std::string, std::string> out;
    for (const auto& node : plan.nodes)
        if (!node.alive) out[node.name] = node.cullReason;
    return out;
}

const ResourcePlan& resource(const CompiledPlan& plan, const std::string& name) {
    for (const auto& r : plan.resources)
        if (r.name == name) return r;
    ADD_FAILURE() << "no resource " << name;
    static const ResourcePlan none;
    return none;
}

bool hasResource(const CompiledPlan& plan, const std::string& name) {
    for (const auto& r : plan.resources)
        if (r.name == name) return true;
    return false;
}

std::vector<std::vector<std::string>> groupNames(const CompiledPlan& plan) {
    std::vector<std::vector<std::string>> out;
    for (const auto& g : plan.aliasGroups) {
        out.emplace_back();
        for (size_t m : g.members) out.back().push_back(plan.resources[m].name);
    }
    return out;
}

struct BarrierView {
    int position;
    std::vector<std::string> initialize;
    std::vector<std::string> hazards;
    bool operator==(const BarrierView&) const = default;
};

std::ostream& operator<<(std::ostream& s, const BarrierView& b) {
    s << "{pos " << b.position << ", init [";
    for (const auto& i : b.initialize) s << i << " ";
    s << "], hazards [";
    for (const auto& h : b.hazards) s << "'" << h << "' ";
    return s << "]}";
}

std::vector<BarrierView> barriers(const CompiledPlan& plan) {
    std::vector<BarrierView> out;
    for (const auto& b : plan.barriers) {
        BarrierView v{b.position, {}, b.hazards};
        for (size_t r : b.initialize) v.initialize.push_back(plan.resources[r].name);
        out.push_back(v);
    }
    return out;
}

constexpr uint64_t kImage64 = 64ull * 64 * kRgba32fBytes;

// src -> f1 -> f2 -> f3 -> f4, output f4.out.
const char* kChain = R"({ "version": 1,
  "passes": [ { "name": "src", "type": "Src" }, { "name": "f1", "type": "Filter" },
              { "name": "f2", "type": "Filter" }, { "name": "f3", "type": "Filter" },
              { "name": "f4", "type": "Filter" } ],
  "edges": [ { "from": "src.color", "to": "f1.in" }, { "from": "f1.out", "to": "f2.in" },
             { "from": "f2.out", "to": "f3.in" }, { "from": "f3.out", "to": "f4.in" } ],
  "outputs": [ "f4.out" ] })";

// src -> a, src -> b, (a, b) -> join.
const char* kDiamond = R"({ "version": 1,
  "passes": [ { "name": "src", "type": "Src" }, { "name": "a", "type": "Filter" },
              { "name": "b", "type": "Filter" }, { "name": "join", "type": "Join" } ],
  "edges": [ { "from": "src.color", "to": "a.in" }, { "from": "src.color", "to": "b.in" },
             { "from": "a.out", "to": "join.a" }, { "from": "b.out", "to": "join.b" } ],
  "outputs": [ "join.out" ] })";

using Names = std::vector<std::string>;
using Reasons = std::map<std::string, std::string>;

}  // namespace

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

// --- resources, lifetimes and aliasing
// ------------------------------------------------------------

TEST(CompilerAlias, ChainSharesMemoryInTwoGroups) {
    CompiledPlan plan = compile(kChain);
    EXPECT_EQ(orderNames(plan), (Names{"src", "f1", "f2", "f3", "f4"}));
    EXPECT_EQ(groupNames(plan),
              (std::vector<Names>{{"src.color", "f2.out"}, {"f1.out", "f3.out"}}));
    for (const auto& g : plan.aliasGroups) EXPECT_EQ(g.bytes, kImage64);
    EXPECT_EQ(resource(plan, "src.color").aliasGroup, 0);
    EXPECT_EQ(resource(plan, "f1.out").aliasGroup, 1);
    EXPECT_EQ(resource(plan, "f2.out").aliasGroup, 0);
    EXPECT_EQ(resource(plan, "f3.out").aliasGroup, 1);
    EXPECT_EQ(resource(plan, "f4.out").aliasGroup, -1);
    EXPECT_EQ(resource(plan, "f4.out").lifetime, Lifetime::Output);
    EXPECT_EQ(plan.transientBytes(), 2 * kImage64);
    EXPECT_EQ(plan.transientBytesWithoutAliasing(), 4 * kImage64);
    EXPECT_EQ(plan.persistentBytes(), kImage64);  // f4.out
}

TEST(CompilerAlias, ChainLifetimes) {
    CompiledPlan plan = compile(kChain);
    struct Expect {
        const char* name;
        int first, last;
        Lifetime lifetime;
    };
    for (const Expect& e :
         {Expect{"src.color", 0, 1, Lifetime::Transient},
          Expect{"f1.out", 1, 2, Lifetime::Transient}, Expect{"f2.out", 2, 3, Lifetime::Transient},
          Expect{"f3.out", 3, 4, Lifetime::Transient}, Expect{"f4.out", 0, 4, Lifetime::Output}}) {
        const ResourcePlan& r = resource(plan, e.name);
        EXPECT_EQ(r.firstUse, e.first) << e.name;
        EXPECT_EQ(r.lastUse, e.last) << e.name;
        EXPECT_EQ(r.lifetime, e.lifetime) << e.name;
        EXPECT_EQ(r.ringSize, 1u) << e.name;
        EXPECT_EQ(r.width, 64u) << e.name;
        EXPECT_EQ(r.height, 64u) << e.name;
        EXPECT_EQ(r.format, testpasses::kRgba32f) << e.name;
        EXPECT_EQ(plan.nodes[r.producer].name + "." + r.field, e.name);
    }
}

TEST(CompilerAlias, DisabledByOption) {
    CompiledPlan plan = compile(kChain, options64(false));
    EXPECT_TRUE(plan.aliasGroups.empty());
    for (const auto& r : plan.resources) EXPECT_EQ(r.aliasGroup, -1) << r.name;
    EXPECT_EQ(plan.transientBytes(), 4 * kImage64);
    EXPECT_EQ(plan.transientBytesWithoutAliasing(), 4 * kImage64);
}

TEST(CompilerAlias, OutputsHistoryPersistentAndCacheableAreNeverAliased) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "Src" }, { "name": "p", "type": "Persist" },
                  { "name": "c", "type": "Cached" }, { "name": "f1", "type": "Filter" },
                  { "name": "f2", "type": "Filter" }, { "name": "j", "type": "Join" },
                  { "name": "k", "type": "Join" } ],
      "edges": [ { "from": "src.color", "to": "p.in" }, { "from": "p.out", "to": "c.in" },
                 { "from": "c.out", "to": "f1.in" }, { "from": "f1.out", "to": "f2.in" },
                 { "from": "f2.out", "to": "j.a" }, { "from": "j.out", "to": "j.b", "delay": 1 },
                 { "from": "f2.out", "to": "k.a" }, { "from": "f1.out", "to": "k.b", "delay": 2 } ],
      "outputs": [ "j.out", "k.out" ] })");
    EXPECT_EQ(orderNames(plan), (Names{"src", "p", "c", "f1", "f2", "j", "k"}));
    EXPECT_EQ(resource(plan, "p.out").lifetime, Lifetime::Persistent);
    EXPECT_EQ(resource(plan, "c.out").lifetime, Lifetime::Persistent);
    EXPECT_EQ(resource(plan, "f1.out").lifetime, Lifetime::History);
    EXPECT_EQ(resource(plan, "f1.out").ringSize, 3u);
    EXPECT_EQ(resource(plan, "j.out").lifetime, Lifetime::History);
    EXPECT_EQ(resource(plan, "j.out").ringSize, 2u);
    EXPECT_EQ(resource(plan, "k.out").lifetime, Lifetime::Output);
    EXPECT_EQ(resource(plan, "src.color").lifetime, Lifetime::Transient);
    EXPECT_EQ(resource(plan, "f2.out").lifetime, Lifetime::Transient);
    for (const char* name : {"p.out", "c.out", "f1.out", "j.out", "k.out"}) {
        EXPECT_EQ(resource(plan, name).aliasGroup, -1) << name;
        // Anything that outlives the frame is live for the whole frame.
        EXPECT_EQ(resource(plan, name).firstUse, 0) << name;
        EXPECT_EQ(resource(plan, name).lastUse, 6) << name;
    }
    // Only the two transients are grouped; their lifetimes [0,1] and [4,6] do not overlap.
    EXPECT_EQ(groupNames(plan), (std::vector<Names>{{"src.color", "f2.out"}}));
    for (const auto& g : plan.aliasGroups)
        for (size_t m : g.members) EXPECT_EQ(plan.resources[m].lifetime, Lifetime::Transient);
    EXPECT_EQ(plan.transientBytes(), kImage64);
    EXPECT_EQ(plan.transientBytesWithoutAliasing(), 2 * kImage64);
    // p.out, c.out, k.out once; f1.out three times; j.out twice.
    EXPECT_EQ(plan.persistentBytes(), (3 + 3 + 2) * kImage64);
}

TEST(CompilerAlias, OverlappingLifetimesNeverShare) {
    CompiledPlan plan = compile(kDiamond);
    // src.color [0,2], a.out [1,3], b.out [2,3] all overlap: three groups of one.
    EXPECT_EQ(groupNames(plan), (std::vector<Names>{{"src.color"}, {"a.out"}, {"b.out"}}));
    EXPECT_EQ(resource(plan, "src.color").lastUse, 2);
    EXPECT_EQ(resource(plan, "a.out").firstUse, 1);
    EXPECT_EQ(resource(plan, "a.out").lastUse, 3);
    EXPECT_EQ(plan.transientBytes(), 3 * kImage64);
    // Every pair of members of one group has disjoint lifetimes (checked generally).
    for (const auto& g : plan.aliasGroups)
        for (size_t i = 1; i < g.members.size(); ++i)
            EXPECT_LT(plan.resources[g.members[i - 1]].lastUse,
                      plan.resources[g.members[i]].firstUse);
}

TEST(CompilerAlias, InternalFieldIsTransientForOnePass) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "Src" }, { "name": "x", "type": "Internal" },
                  { "name": "f", "type": "Filter" } ],
      "edges": [ { "from": "src.color", "to": "x.in" }, { "from": "x.out", "to": "f.in" } ],
      "outputs": [ "f.out" ] })",
                                {33, 17, 0, true});
    const ResourcePlan& s = resource(plan, "x.scratch");
    EXPECT_EQ(s.lifetime, Lifetime::Transient);
    EXPECT_EQ(s.firstUse, 1);
    EXPECT_EQ(s.lastUse, 1);
    EXPECT_EQ(s.width, 33u);
    EXPECT_EQ(s.height, 17u);
    EXPECT_EQ(s.format, vk::Format::eR32Sfloat);
    EXPECT_EQ(s.bytes(), 33u * 17 * 4);
    EXPECT_GE(s.aliasGroup, 0);
    EXPECT_EQ(plan.resourceOf.at({plan.findNode("x"), "scratch"}),
              size_t(&s - plan.resources.data()));
}

TEST(CompilerAlias, BuffersAreResourcesButNotAliased) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "bp", "type": "BufferProducer" }, { "name": "bc", "type": "BufferConsumer" } ],
      "edges": [ { "from": "bp.buf", "to": "bc.buf" } ], "outputs": [ "bc.color" ] })");
    const ResourcePlan& b = resource(plan, "bp.buf");
    EXPECT_FALSE(b.isImage);
    EXPECT_EQ(b.bufferBytes, 4096u);
    EXPECT_EQ(b.bytes(), 4096u);
    EXPECT_EQ(b.lifetime, Lifetime::Transient);
    EXPECT_EQ(b.aliasGroup, -1);
    EXPECT_EQ(b.firstUse, 0);
    EXPECT_EQ(b.lastUse, 1);
    EXPECT_TRUE(plan.aliasGroups.empty());
    EXPECT_EQ(plan.transientBytes(), 4096u);
    EXPECT_EQ(plan.transientBytesWithoutAliasing(), 4096u);
    ASSERT_EQ(plan.barriers.size(), 1u);
    EXPECT_EQ(plan.barriers[0].hazards, (Names{"RAW bc.buf <- bp.buf"}));
}

// --- barriers
// -------------------------------------------------------------------------------------

TEST(CompilerBarriers, ChainHasRawBarrierBeforeEveryConsumer) {
    CompiledPlan plan = compile(kChain, options64(false));
    EXPECT_EQ(barriers(plan), (std::vector<BarrierView>{
                                  {1, {}, {"RAW f1.in <- src.color"}},
                                  {2, {}, {"RAW f2.in <- f1.out"}},
                                  {3, {}, {"RAW f3.in <- f2.out"}},
                                  {4, {}, {"RAW f4.in <- f3.out"}},
                              }));
}

TEST(CompilerBarriers, ChainWithAliasingInitializesAtFirstUse) {
    CompiledPlan plan = compile(kChain);
    EXPECT_EQ(barriers(plan),
              (std::vector<BarrierView>{
                  {0, {"src.color"}, {}},
                  {1, {"f1.out"}, {"RAW f1.in <- src.color"}},
                  {2,
                   {"f2.out"},
                   {"RAW f2.in <- f1.out", "WAR alias f2.out reuses the memory of src.color"}},
                  {3,
                   {"f3.out"},
                   {"RAW f3.in <- f2.out", "WAR alias f3.out reuses the memory of f1.out"}},
                  {4, {}, {"RAW f4.in <- f3.out"}},
              }));
}

TEST(CompilerBarriers, DiamondNeedsBarriersOnlyBeforeAAndJoin) {
    CompiledPlan plan = compile(kDiamond, options64(false));
    EXPECT_EQ(orderNames(plan), (Names{"src", "a", "b", "join"}));
    // The barrier before a already covers src's write for b; join reads a (written after that
    // barrier) and b.
    EXPECT_EQ(barriers(plan), (std::vector<BarrierView>{
                                  {1, {}, {"RAW a.in <- src.color"}},
                                  {3, {}, {"RAW join.a <- a.out", "RAW join.b <- b.out"}},
                              }));
}

TEST(CompilerBarriers, EveryUndelayedReadIsCoveredByABarrier) {
    // The invariant behind the barrier plan, checked on several graphs: for every undelayed input
    // there is a barrier at a position p with writer < p <= reader.
    for (const char* graph : {kChain, kDiamond}) {
        for (bool aliasing : {false, true}) {
            CompiledPlan plan = compile(graph, options64(aliasing));
            for (const auto& [key, src] : plan.inputs) {
                if (src.delay > 0) continue;
                int reader = plan.positionOf(key.first), writer = plan.positionOf(src.node);
                bool covered = false;
                for (const auto& b : plan.barriers)
                    covered |= b.position > writer && b.position <= reader;
                EXPECT_TRUE(covered) << plan.nodes[key.first].name << "." << key.second << " reads "
                                     << plan.nodes[src.node].name << "." << src.field
                                     << " (aliasing " << aliasing << ")";
            }
        }
    }
}

TEST(CompilerBarriers, DelayedReadNeedsNoBarrier) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "Src" }, { "name": "j", "type": "Join" } ],
      "edges": [ { "from": "src.color", "to": "j.a" }, { "from": "j.out", "to": "j.b", "delay": 1 } ],
      "outputs": [ "j.out" ] })",
                                options64(false));
    EXPECT_EQ(barriers(plan), (std::vector<BarrierView>{{1, {}, {"RAW j.a <- src.color"}}}));
}

// --- history rings
// --------------------------------------------------------------------------------

namespace {

const char* kSelfLoop = R"({ "version": 1,
  "passes": [ { "name": "src", "type": "Src" }, { "name": "j", "type": "Join" } ],
  "edges": [ { "from": "src.color", "to": "j.a" }, { "from": "j.out", "to": "j.b", "delay": %s } ],
  "outputs": [ "j.out" ] })";

std::string selfLoop(const char* delay) {
    std::string text = kSelfLoop;
    text.replace(text.find("%s"), 2, delay);
    return text;
}

}  // namespace

TEST(CompilerHistory, SelfLoopWithDelayOne) {
    CompiledPlan plan = compile(selfLoop("1"));
    EXPECT_EQ(orderNames(plan), (Names{"src", "j"}));
    const ResourcePlan& r = resource(plan, "j.out");
    EXPECT_EQ(r.lifetime, Lifetime::History);  // history wins over "output"
    EXPECT_EQ(r.ringSize, 2u);
    EXPECT_EQ(r.aliasGroup, -1);
    EXPECT_EQ(r.firstUse, 0);
    EXPECT_EQ(r.lastUse, 1);
    const InputSource& b = plan.inputs.at({plan.findNode("j"), "b"});
    EXPECT_EQ(b.delay, 1u);
    EXPECT_EQ(b.node, plan.findNode("j"));
    EXPECT_EQ(b.resource, plan.resourceOf.at({plan.findNode("j"), "out"}));
    EXPECT_EQ(b.pointer, "/edges/1");
    EXPECT_EQ(plan.persistentBytes(), 2 * kImage64);
    EXPECT_EQ(plan.transientBytes(), kImage64);  // src.color
}

TEST(CompilerHistory, DelayThreeNeedsRingOfFour) {
    CompiledPlan plan = compile(selfLoop("3"));
    EXPECT_EQ(resource(plan, "j.out").lifetime, Lifetime::History);
    EXPECT_EQ(resource(plan, "j.out").ringSize, 4u);
    EXPECT_EQ(resource(plan, "j.out").aliasGroup, -1);
    EXPECT_EQ(plan.persistentBytes(), 4 * kImage64);
}

TEST(CompilerHistory, RingSizeIsTheLongestDelayPlusOne) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "Src" }, { "name": "f", "type": "Filter" },
                  { "name": "j", "type": "Join" }, { "name": "k", "type": "Join" } ],
      "edges": [ { "from": "src.color", "to": "f.in" }, { "from": "src.color", "to": "j.a" },
                 { "from": "f.out", "to": "j.b", "delay": 2 }, { "from": "src.color", "to": "k.a" },
                 { "from": "f.out", "to": "k.b", "delay": 5 } ],
      "outputs": [ "j.out", "k.out" ] })");
    EXPECT_EQ(resource(plan, "f.out").lifetime, Lifetime::History);
    EXPECT_EQ(resource(plan, "f.out").ringSize, 6u);
    EXPECT_EQ(resource(plan, "f.out").aliasGroup, -1);
}

TEST(CompilerHistory, UndelayedSelfLoopIsACycle) {
    EXPECT_NE(compileError(selfLoop("0")).find("/edges/1: cycle without delay: j -> j"),
              std::string::npos);
}

// --- sizes
// ----------------------------------------------------------------------------------------

namespace {

const char* kHalfChain = R"({ "version": 1,
  "passes": [ { "name": "src", "type": "Src" }, { "name": "h", "type": "Half" },
              { "name": "f1", "type": "Filter" }, { "name": "f2", "type": "Filter" },
              { "name": "x", "type": "Internal" } ],
  "edges": [ { "from": "src.color", "to": "h.in" }, { "from": "h.out", "to": "f1.in" },
             { "from": "f1.out", "to": "f2.in" }, { "from": "f2.out", "to": "x.in" } ],
  "outputs": [ "x.out" ] })";

}  // namespace

TEST(CompilerSizes, ScaledHalfAt64) {
    CompiledPlan plan = compile(kHalfChain);
    EXPECT_EQ(resource(plan, "src.color").width, 64u);
    EXPECT_EQ(resource(plan, "h.out").width, 32u);
    EXPECT_EQ(resource(plan, "h.out").height, 32u);
    EXPECT_EQ(resource(plan, "h.out").bytes(), 32u * 32 * kRgba32fBytes);
}

TEST(CompilerSizes, ScaledRoundsUpAndSameAsPropagates) {
    CompiledPlan plan = compile(kHalfChain, {33, 17, 0, true});
    EXPECT_EQ(resource(plan, "src.color").width, 33u);
    EXPECT_EQ(resource(plan, "src.color").height, 17u);
    for (const char* name : {"h.out", "f1.out", "f2.out", "x.scratch", "x.out"}) {
        EXPECT_EQ(resource(plan, name).width, 17u) << name;  // ceil(33 / 2)
        EXPECT_EQ(resource(plan, name).height, 9u) << name;  // ceil(17 / 2)
    }
}

TEST(CompilerSizes, ScaledIsAtLeastOnePixel) {
    CompiledPlan plan = compile(kHalfChain, {1, 1, 0, true});
    EXPECT_EQ(resource(plan, "h.out").width, 1u);
    EXPECT_EQ(resource(plan, "h.out").height, 1u);
}

TEST(CompilerSizes, FixedSizeAndSameAsOfFixed) {
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "Src" }, { "name": "fx", "type": "Fixed" },
                  { "name": "f", "type": "Filter" } ],
      "edges": [ { "from": "src.color", "to": "fx.in" }, { "from": "fx.out", "to": "f.in" } ],
      "outputs": [ "f.out" ] })");
    EXPECT_EQ(resource(plan, "fx.out").width, 17u);
    EXPECT_EQ(resource(plan, "fx.out").height, 9u);
    EXPECT_EQ(resource(plan, "f.out").width, 17u);
    EXPECT_EQ(resource(plan, "f.out").height, 9u);
}

TEST(CompilerSizes, SameAsThroughDelayedEdgeFromALaterPass) {
    // j runs first (file order, delayed input) but is sized like h's output, resolved later.
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "j", "type": "Join" }, { "name": "src", "type": "Src" },
                  { "name": "h", "type": "Half" } ],
      "edges": [ { "from": "h.out", "to": "j.a", "delay": 1 }, { "from": "src.color", "to": "h.in" } ],
      "outputs": [ "j.out" ] })");
    EXPECT_EQ(orderNames(plan), (Names{"j", "src", "h"}));
    EXPECT_EQ(resource(plan, "j.out").width, 32u);
    EXPECT_EQ(resource(plan, "j.out").height, 32u);
    EXPECT_EQ(resource(plan, "h.out").lifetime, Lifetime::History);
}

TEST(CompilerSizes, OutputSizedLikeConnectedInput) {
    // j.b is open: j.out is sized like j.a (32x32), not like the screen.
    CompiledPlan plan = compile(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "Src" }, { "name": "h", "type": "Half" },
                  { "name": "j", "type": "Join" } ],
      "edges": [ { "from": "src.color", "to": "h.in" }, { "from": "h.out", "to": "j.a" } ],
      "outputs": [ "j.out" ] })");
    EXPECT_EQ(resource(plan, "j.out").width, 32u);
}

TEST(CompilerSizes, SizeMismatchIsAnError) {
    std::string msg = compileError(R"({ "version": 1,
      "passes": [ { "name": "src", "type": "Src" }, { "name": "h", "type": "Half" },
                  { "name": "j", "type": "Join" } ],
      "edges": [ { "from": "src.color", "to": "h.in" }, { "from": "src.color", "to": "j.a" },
                 { "from": "h.out", "to": "j.b" } ],
      "outputs": [ "j.out" ] })");
    EXPECT_EQ(msg,
              "test.json: /edges/2: size mismatch: 'h.out' is 32x32 but 'j.b' expects 64x64 "
              "(same-as-input 'a')");
}

// --- dumps
// ----------------------------------------------------------------------------------------

namespace {

const char* kDumpGraph = R"({ "version": 1,
  "passes": [ { "name": "src", "type": "Src" }, { "name": "f1", "type": "Filter" },
              { "name": "f2", "type": "Filter" }, { "name": "f3", "type": "Filter" },
              { "name": "f4", "type": "Filter" }, { "name": "x", "type": "Filter" },
              { "name": "off", "type": "Filter", "enabled": false } ],
  "edges": [ { "from": "src.color", "to": "f1.in" }, { "from": "f1.out", "to": "f2.in" },
             { "from": "f2.out", "to": "f3.in" }, { "from": "f3.out", "to": "f4.in" },
             { "from": "src.color", "to": "x.in" }, { "from": "src.color", "to": "off.in" } ],
  "outputs": [ "f4.out" ] })";

}  // namespace

TEST(CompilerDump, Text) {
    CompiledPlan plan = compile(kDumpGraph);
    std::string text = dumpPlanText(plan);
    for (const char* expected : {
             "graph test.json at 64x64\n",
             "order:\n  0. src (Src)\n",
             "  1. f1 (Filter)\n",
             "     | barrier: WAR alias f2.out reuses the memory of src.color\n  2. f2 (Filter)\n",
             "culled:\n",
             "  x (Filter): reaches no marked output\n",
             "  off (Filter): disabled in the graph file (\"enabled\": false)\n",
             "  src.color  64x64 rgba32f  transient  live [0, 1]  alias group 0\n",
             "  f3.out  64x64 rgba32f  transient  live [3, 4]  alias group 1\n",
             "  f4.out  64x64 rgba32f  output  live [0, 4]\n",
             "memory: transient 131072 B (without aliasing 262144 B), persistent 65536 B (of which "
             "history 0 B)\n",
         })
        EXPECT_NE(text.find(expected), std::string::npos) << "missing: " << expected << "\nin:\n"
                                                          << text;
    // Order before culled before resources before memory.
    EXPECT_LT(text.find("order:"), text.find("culled:"));
    EXPECT_LT(text.find("culled:"), text.find("resources:"));
    EXPECT_LT(text.find("resources:"), text.find("memory:"));
}

TEST(CompilerDump, TextShowsRings) {
    std::string text = dumpPlanText(compile(selfLoop("3")));
    EXPECT_NE(text.find("  j.out  64x64 rgba32f  history ring 4  live [0, 1]\n"), std::string::npos)
        << text;
    EXPECT_EQ(text.find("culled:"), std::string::npos);
}

TEST(CompilerDump, Json) {
    CompiledPlan plan = compile(kDumpGraph);
    nlohmann::json j = dumpPlanJson(plan);
    EXPECT_EQ(j["file"], "test.json");
    EXPECT_EQ(j["size"], nlohmann::json::array({64, 64}));
    EXPECT_EQ(j["aliasing"], true);
    EXPECT_EQ(j["order"], nlohmann::json::array({"src", "f1", "f2", "f3", "f4"}));

    ASSERT_EQ(j["passes"].size(), 7u);
    EXPECT_EQ(j["passes"][0]["name"], "src");
    EXPECT_EQ(j["passes"][0]["type"], "Src");
    EXPECT_EQ(j["passes"][0]["alive"], true);
    EXPECT_EQ(j["passes"][0]["position"], 0);
    EXPECT_FALSE(j["passes"][0].contains("reason"));
    EXPECT_EQ(j["passes"][4]["position"], 4);
    EXPECT_EQ(j["passes"][5]["name"], "x");
    EXPECT_EQ(j["passes"][5]["alive"], false);
    EXPECT_EQ(j["passes"][5]["reason"], "reaches no marked output");
    EXPECT_EQ(j["passes"][5]["position"], -1);
    EXPECT_EQ(j["passes"][6]["reason"], "disabled in the graph file (\"enabled\": false)");

    ASSERT_EQ(j["resources"].size(), 5u);
    nlohmann::json src = j["resources"][0];
    EXPECT_EQ(src["name"], "src.color");
    EXPECT_EQ(src["lifetime"], "transient");
    EXPECT_EQ(src["first_use"], 0);
    EXPECT_EQ(src["last_use"], 1);
    EXPECT_EQ(src["alias_group"], 0);
    EXPECT_EQ(src["ring"], 1);
    EXPECT_EQ(src["bytes"], kImage64);
    EXPECT_EQ(src["size"], nlohmann::json::array({64, 64}));
    EXPECT_EQ(src["format"], "rgba32f");
    EXPECT_EQ(j["resources"][4]["name"], "f4.out");
    EXPECT_EQ(j["resources"][4]["lifetime"], "output");
    EXPECT_EQ(j["resources"][4]["alias_group"], -1);

    ASSERT_EQ(j["alias_groups"].size(), 2u);
    EXPECT_EQ(j["alias_groups"][0]["bytes"], kImage64);
    EXPECT_EQ(j["alias_groups"][0]["members"], nlohmann::json::array({"src.color", "f2.out"}));
    EXPECT_EQ(j["alias_groups"][1]["members"], nlohmann::json::array({"f1.out", "f3.out"}));

    // (The exact barrier list is CompilerBarriers' business; here: the fields of one entry.)
    nlohmann::json atF2;
    for (const auto& b : j["barriers"])
        if (b["position"] == 2) atF2 = b;
    ASSERT_TRUE(atF2.is_object()) << j["barriers"].dump();
    EXPECT_EQ(atF2["before"], "f2");
    EXPECT_EQ(atF2["initialize"], nlohmann::json::array({"f2.out"}));
    EXPECT_NE(std::find(atF2["hazards"].begin(), atF2["hazards"].end(),
                        "WAR alias f2.out reuses the memory of src.color"),
              atF2["hazards"].end());
    const nlohmann::json& first = j["barriers"][0];
    EXPECT_EQ(first["before"], "src");
    EXPECT_EQ(first["initialize"], nlohmann::json::array({"src.color"}));

    EXPECT_EQ(j["memory"]["transient_bytes"], 2 * kImage64);
    EXPECT_EQ(j["memory"]["transient_bytes_without_aliasing"], 4 * kImage64);
    EXPECT_EQ(j["memory"]["persistent_bytes"], kImage64);
}

TEST(CompilerDump, JsonBuffer) {
    nlohmann::json j = dumpPlanJson(compile(R"({ "version": 1,
      "passes": [ { "name": "bp", "type": "BufferProducer" }, { "name": "bc", "type": "BufferConsumer" } ],
      "edges": [ { "from": "bp.buf", "to": "bc.buf" } ], "outputs": [ "bc.color" ] })"));
    EXPECT_EQ(j["resources"][0]["name"], "bp.buf");
    EXPECT_EQ(j["resources"][0]["buffer_bytes"], 4096);
    EXPECT_FALSE(j["resources"][0].contains("size"));
    EXPECT_FALSE(j["resources"][0].contains("format"));
}
