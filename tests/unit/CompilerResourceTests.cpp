// Compile stages 6-7 (core/graph/CompileResources, CompileAliasing): lifetimes and aliasing of
// transient images, history rings of delayed edges, size rules. CPU only.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "tests/unit/CompilerTestUtil.h"

using namespace fovea;
using namespace fovea::graph;
using namespace fovea::compilertest;

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
// --- history rings
// --------------------------------------------------------------------------------

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
