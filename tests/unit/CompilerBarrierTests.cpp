// Compile stage 8 (core/graph/CompileBarriers): where barriers go and why. CPU only.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "tests/unit/CompilerTestUtil.h"

using namespace fovea;
using namespace fovea::graph;
using namespace fovea::compilertest;

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
