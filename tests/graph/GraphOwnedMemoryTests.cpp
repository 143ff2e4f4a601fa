// GPU tests of graph-owned buffers (docs/architecture.md "The pass contract"): a pass's memory
// is a field the plan lists, with the usage and initial content the field declares
// (FieldBuilder::indirect, hostVisible, zeroed, zeroOnReset, contents, sizedBy), and a pass that
// allocates device memory itself is counted (PassRecord::allocationsOutsidePlan, report.json).
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/vk/Resources.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::graph;

namespace {

constexpr vk::Format kRgba32f = vk::Format::eR32G32B32A32Sfloat;
constexpr std::array<uint32_t, 4> kTable = {11, 22, 33, 44};

// A fixed 20x12 image (cleared), so a buffer can be sized by an input smaller than the screen.
class SmallImagePass : public Pass {
public:
    void reflect(Reflection& r) const override { r.output("color", kRgba32f).fixed(20, 12); }
    void execute(ExecuteContext& ctx) override {
        ctx.image("color").recordClear(ctx.cmd(), {0.0f, 0.0f, 0.0f, 0.0f});
    }
};

// Declares one buffer of each initial content. execute() writes frame index + 1 into word
// (index % 4) of `zero` and `reset`, so the words show which frames the graph cleared them.
class InitPass : public Pass {
public:
    void reflect(Reflection& r) const override {
        r.input("color").optional();
        r.output("out", kRgba32f);
        r.internal("zero", vk::Format::eUndefined).buffer(16).persistent().zeroed();
        r.internal("reset", vk::Format::eUndefined).buffer(16).persistent().zeroOnReset();
        r.internal("table", vk::Format::eUndefined)
            .buffer(sizeof(kTable))
            .contents(kTable.data(), sizeof(kTable));
        r.internal("args", vk::Format::eUndefined).buffer(16).indirect();
        r.internal("mapped", vk::Format::eUndefined).buffer(16).hostVisible();
        r.internal("blocks", vk::Format::eUndefined).bufferPerBlock(8, 4, 16).sizedBy("color");
    }
    void execute(ExecuteContext& ctx) override {
        const uint64_t i = ctx.frame().index;
        for (const char* field : {"zero", "reset"})
            ctx.cmd().fillBuffer(ctx.buffer(field).buffer(), 4 * (i % 4), 4, uint32_t(i + 1));
        ctx.image("out").recordClear(ctx.cmd(), {0.0f, 0.0f, 0.0f, 0.0f});
    }
};

// Breaks the contract: one buffer of its own in compile(), one more in every execute().
class RoguePass : public Pass {
public:
    void reflect(Reflection& r) const override { r.output("out", kRgba32f); }
    void compile(CompileContext& ctx) override {
        mOwn.push_back(std::make_unique<gpu::Buffer>(ctx.gpu(), 64));
    }
    void execute(ExecuteContext& ctx) override {
        mOwn.push_back(std::make_unique<gpu::Buffer>(ctx.gpu(), 64));
        ctx.image("out").recordClear(ctx.cmd(), {1.0f, 0.0f, 0.0f, 1.0f});
    }

private:
    std::vector<std::unique_ptr<gpu::Buffer>> mOwn;
};

// A field declaration mistake: indirect usage on an image.
class IndirectImagePass : public Pass {
public:
    void reflect(Reflection& r) const override { r.output("out", kRgba32f).indirect(); }
    void execute(ExecuteContext&) override {}
};

const PassRegistry& registry() {
    static const PassRegistry r = [] {
        PassRegistry reg;
        reg.add({"SmallImage", "", [] { return std::make_unique<SmallImagePass>(); }});
        reg.add({"Init", "", [] { return std::make_unique<InitPass>(); }});
        reg.add({"Rogue", "", [] { return std::make_unique<RoguePass>(); }});
        reg.add({"IndirectImage", "", [] { return std::make_unique<IndirectImagePass>(); }});
        return reg;
    }();
    return r;
}

GraphDesc testGraph(const std::string& passes, const std::string& edges,
                    const std::string& outputs) {
    return parseGraphText(R"({ "version": 1, "passes": [ )" + passes + R"( ], "edges": [ )" +
                              edges + R"( ], "outputs": [ )" + outputs + " ] }",
                          "graph_owned_memory_test.json");
}

CompileOptions sized(uint32_t w, uint32_t h) {
    CompileOptions o;
    o.width = w;
    o.height = h;
    return o;
}

std::vector<uint32_t> words(const gpu::Context& ctx, const RenderGraph& g, const char* name) {
    return g.buffer(name).downloadAs<uint32_t>(ctx);
}

using Words = std::vector<uint32_t>;

class GraphOwnedMemory : public GpuTest {};

}  // namespace

TEST_F(GraphOwnedMemory, BuffersGetTheirDeclaredUsageAndContent) {
    RenderGraph g(ctx(), registry());
    const std::string init = R"({ "name": "b", "type": "Init" })";
    g.build(testGraph(init, "", R"("b.out")"), sized(64, 64));
    EXPECT_EQ(words(ctx(), g, "b.table"), Words(kTable.begin(), kTable.end()));
    EXPECT_TRUE(g.buffer("b.args").usage() & vk::BufferUsageFlagBits::eIndirectBuffer);
    EXPECT_FALSE(g.buffer("b.zero").usage() & vk::BufferUsageFlagBits::eIndirectBuffer);
    EXPECT_NE(g.buffer("b.mapped").mapped(), nullptr);
    EXPECT_EQ(g.buffer("b.zero").mapped(), nullptr);
    // An open sizing input: the render size, 8x8 blocks of 64x64.
    EXPECT_EQ(g.buffer("b.blocks").size(), 16u + 4u * 8u * 8u);

    g.runFrame();  // frame 0: both zeroed on their first frame, then word 0 = 1
    g.runFrame();  // frame 1: nothing cleared, word 1 = 2
    EXPECT_EQ(words(ctx(), g, "b.zero"), Words({1, 2, 0, 0}));
    EXPECT_EQ(words(ctx(), g, "b.reset"), Words({1, 2, 0, 0}));
    g.reset();
    g.runFrame();  // frame 2 starts a history: only `reset` is zeroed before word 2 = 3
    EXPECT_EQ(words(ctx(), g, "b.zero"), Words({1, 2, 3, 0}));
    EXPECT_EQ(words(ctx(), g, "b.reset"), Words({0, 0, 3, 0}));
    EXPECT_EQ(words(ctx(), g, "b.table"), Words(kTable.begin(), kTable.end()));
    EXPECT_EQ(g.records()[g.plan().findNode("b")].allocationsOutsidePlan, 0u);
}

TEST_F(GraphOwnedMemory, ABufferSizedByAnInputFollowsThatImage) {
    RenderGraph g(ctx(), registry());
    g.build(testGraph(R"({ "name": "s", "type": "SmallImage" }, { "name": "b", "type": "Init" })",
                      R"({ "from": "s.color", "to": "b.color" })", R"("b.out")"),
            sized(64, 64));
    // 20x12 in 8x8 blocks: 3 x 2, not the 8 x 8 blocks of the screen.
    EXPECT_EQ(g.buffer("b.blocks").size(), 16u + 4u * 3u * 2u);
}

TEST_F(GraphOwnedMemory, APassAllocatingItsOwnMemoryIsCounted) {
    RenderGraph g(ctx(), registry());
    g.build(testGraph(R"({ "name": "r", "type": "Rogue" }, { "name": "b", "type": "Init" })", "",
                      R"("r.out", "b.out")"),
            sized(16, 16));
    const size_t rogue = g.plan().findNode("r"), init = g.plan().findNode("b");
    EXPECT_EQ(g.records()[rogue].allocationsOutsidePlan, 1u);  // compile()
    g.runFrame();
    g.runFrame();
    EXPECT_EQ(g.records()[rogue].allocationsOutsidePlan, 3u);  // + one per execute()
    EXPECT_EQ(g.records()[init].allocationsOutsidePlan, 0u);
}

TEST_F(GraphOwnedMemory, BufferUsageOnAnImageIsAPassAuthorError) {
    RenderGraph g(ctx(), registry());
    try {
        g.build(testGraph(R"({ "name": "i", "type": "IndirectImage" })", "", R"("i.out")"),
                sized(8, 8));
        FAIL() << "an image field declared indirect() was accepted";
    } catch (const std::logic_error& e) {
        EXPECT_NE(std::string(e.what()).find("field 'out'"), std::string::npos) << e.what();
    }
}
