// The CPU side of the pass contract's newer parts (core/graph/Reflection, Compile*.cpp,
// PlanDump.cpp): pass-declared history (ring sizes, lifetime, memory figures, dump), buffer sizes
// that follow the render size, Pass::validate (parameters checked at compile, errors naming
// /passes/i/params/<name>), and camera-only passes that run without a scene. No GPU.
#include <gtest/gtest.h>

#include <string>

#include "tests/unit/CompilerTestUtil.h"

using namespace fovea;
using namespace fovea::graph;
using namespace fovea::compilertest;

namespace {

CompileOptions sized(uint32_t w, uint32_t h) {
    CompileOptions o;
    o.width = w;
    o.height = h;
    return o;
}

const char* kTemporalGraph = R"({ "version": 1, "passes": [
    { "name": "src", "type": "Src" }, { "name": "t", "type": "Temporal" } ],
  "edges": [ { "from": "src.color", "to": "t.in" } ], "outputs": [ "t.out" ] })";

constexpr uint64_t kRgba32f64 = 64ull * 64 * 16, kR32f64 = 64ull * 64 * 4;

}  // namespace

TEST(CompilerHistory, DeclaredHistoryMakesARingWithoutAnyEdge) {
    CompiledPlan plan = compile(kTemporalGraph);
    const ResourcePlan& out = resource(plan, "t.out");
    EXPECT_EQ(out.lifetime, Lifetime::History);
    EXPECT_EQ(out.declaredHistory, 2u);
    EXPECT_EQ(out.ringSize, 3u);
    EXPECT_EQ(out.aliasGroup, -1);  // never shares memory: its slots outlive the frame
    const ResourcePlan& state = resource(plan, "t.state");
    EXPECT_EQ(state.lifetime, Lifetime::History);
    EXPECT_EQ(state.ringSize, 2u);
    // Memory figures: every slot counts as persistent, the previous-frame slots as history.
    EXPECT_EQ(plan.historyBytes(), 2 * kRgba32f64 + kR32f64);
    EXPECT_EQ(plan.persistentBytes(), 3 * kRgba32f64 + 2 * kR32f64);
}

TEST(CompilerHistory, DelayEdgeOnADeclaredHistoryWidensTheRing) {
    // A consumer reading 4 frames back through a delay edge needs a longer ring than the 2
    // frames the producer declared; the declared count stays what the pass asked for.
    CompiledPlan plan = compile(R"({ "version": 1, "passes": [
        { "name": "src", "type": "Src" }, { "name": "t", "type": "Temporal" },
        { "name": "f", "type": "Filter" } ],
      "edges": [ { "from": "src.color", "to": "t.in" },
                 { "from": "t.out", "to": "f.in", "delay": 4 } ], "outputs": [ "f.out" ] })");
    const ResourcePlan& out = resource(plan, "t.out");
    EXPECT_EQ(out.ringSize, 5u);
    EXPECT_EQ(out.declaredHistory, 2u);
}

TEST(CompilerHistory, DumpsShowDeclaredHistoryAndItsBytes) {
    CompiledPlan plan = compile(kTemporalGraph);
    const std::string text = dumpPlanText(plan);
    EXPECT_NE(text.find("t.out  64x64 rgba32f  history ring 3 (pass keeps 2 previous frames)"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("(of which history " + std::to_string(plan.historyBytes()) + " B)"),
              std::string::npos)
        << text;
    const auto json = dumpPlanJson(plan);
    EXPECT_EQ(json["memory"]["history_bytes"], plan.historyBytes());
    bool found = false;
    for (const auto& r : json["resources"])
        if (r["name"] == "t.state") {
            found = true;
            EXPECT_EQ(r["declared_history"], 1);
            EXPECT_EQ(r["ring"], 2);
        }
    EXPECT_TRUE(found);
}

TEST(CompilerHistory, HistoryOnAnInputIsAPassAuthorError) {
    EXPECT_THROW(compile(R"({ "version": 1, "passes": [
        { "name": "src", "type": "Src" }, { "name": "h", "type": "HistoryOnInput" } ],
      "edges": [ { "from": "src.color", "to": "h.in" } ], "outputs": [ "h.out" ] })"),
                 std::logic_error);
}

TEST(CompilerHistory, PreviousBindingNames) {
    EXPECT_EQ(previousBindingName("result", 1), "prev_result");
    EXPECT_EQ(previousBindingName("hist_accum", 3), "prev3_hist_accum");
    EXPECT_EQ(parsePreviousBindingName("prev_result"), std::make_pair(std::string("result"), 1u));
    EXPECT_EQ(parsePreviousBindingName("prev3_hist_accum"),
              std::make_pair(std::string("hist_accum"), 3u));
    for (const char* other : {"previous", "prev_", "prev1_x", "prevx_y", "result", "prev12345_x"})
        EXPECT_EQ(parsePreviousBindingName(other).second, 0u) << other;
}

TEST(CompilerBufferSize, BuffersFollowTheRenderSize) {
    const char* graph = R"({ "version": 1, "passes": [ { "name": "b", "type": "SizedBuffers" } ],
      "outputs": [ "b.list", "b.blocks" ] })";
    for (auto [w, h] : {std::pair{64u, 64u}, std::pair{100u, 33u}, std::pair{1u, 1u}}) {
        CompiledPlan plan = compile(graph, sized(w, h));
        EXPECT_EQ(resource(plan, "b.list").bufferBytes, 16 + 8ull * w * h) << w << "x" << h;
        const uint64_t blocks = ((w + 31) / 32 + 1) * ((h + 31) / 32 + 1);
        EXPECT_EQ(resource(plan, "b.blocks").bufferBytes, 384 * blocks) << w << "x" << h;
    }
    BufferSize fixed{.header = 4096};
    EXPECT_EQ(fixed.bytes(640, 480), 4096u);
}

TEST(CompilerValidate, ParameterChecksAreInputErrorsWithThePointer) {
    auto graph = [](const std::string& params, bool aux) {
        return std::string(R"({ "version": 1, "passes": [ { "name": "src", "type": "Src" },
            { "name": "c", "type": "Checked", "params": )") +
               params + R"( } ], "edges": [ { "from": "src.color", "to": "c.in" })" +
               (aux ? R"(, { "from": "src.color", "to": "c.aux" })" : "") +
               R"( ], "outputs": [ "c.out" ] })";
    };
    EXPECT_EQ(compileError(graph(R"({ "lo": 1, "hi": 2 })", false)), "<no error>");
    const std::string order = compileError(graph(R"({ "lo": 5, "hi": 2 })", false));
    EXPECT_NE(order.find("test.json: /passes/1/params/hi"), std::string::npos) << order;
    EXPECT_NE(order.find("pass 'c' (Checked): params.hi: must be >= lo"), std::string::npos)
        << order;
    const std::string aux = compileError(graph(R"({ "useAux": true })", false));
    EXPECT_NE(aux.find("/passes/1/params/useAux"), std::string::npos) << aux;
    EXPECT_EQ(compileError(graph(R"({ "useAux": true })", true)), "<no error>");
}

TEST(CompilerValidate, CulledPassesAreNotValidated) {
    // A pass that is culled (reaches no output) never runs, so its cross-checks do not apply.
    EXPECT_EQ(compileError(R"({ "version": 1, "passes": [ { "name": "src", "type": "Src" },
        { "name": "c", "type": "Checked", "params": { "lo": 5, "hi": 2 } } ],
      "edges": [ { "from": "src.color", "to": "c.in" } ], "outputs": [ "src.color" ] })"),
              "<no error>");
}

TEST(CompilerCull, CameraOnlyPassRunsWithoutAScene) {
    CompiledPlan plan =
        compile(R"({ "version": 1, "passes": [ { "name": "m", "type": "CameraOnly" } ],
      "outputs": [ "m.mask" ] })");
    EXPECT_TRUE(plan.nodes[plan.findNode("m")].alive) << plan.nodes[plan.findNode("m")].cullReason;
}
