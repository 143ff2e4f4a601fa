// The barriers between one pass's dispatches are derived by the graph (gpu::DispatchHazards,
// docs/architecture.md "Barriers between the dispatches of one pass") and counted in report.json
// (`dispatches`, `barriers_in_pass`). Per frame, each multi-dispatch pass gets exactly the
// barriers its data flow needs: a count that drops means a dependency went unseen (e.g. a shader
// binding declared `readonly` that is written), one that grows means work serialized for nothing.
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

struct PerFrame {
    uint64_t dispatches, barriers;
};

// name -> per-frame (dispatches, barriers) of a 2-frame run at 32x32.
std::map<std::string, PerFrame> countsPerFrame(const std::string& graph) {
    TempDir tmp;
    const Result r = runSmall(kRepo / "graphs" / graph, tmp / "out", {"--save-frames", "none"});
    EXPECT_EQ(r.code, 0) << r.describe();
    std::map<std::string, PerFrame> out;
    if (r.code != 0) return out;
    const json report = readReport(tmp / "out");
    for (const auto& p : report.at("passes")) {
        const uint64_t runs = p.at("executions");
        EXPECT_EQ(runs, 2u) << graph << ": " << p.at("name");
        if (runs == 0) continue;
        out[p.at("name")] = {p.at("dispatches").get<uint64_t>() / runs,
                             p.at("barriers_in_pass").get<uint64_t>() / runs};
    }
    return out;
}

void expectCounts(const std::string& graph, const std::map<std::string, PerFrame>& expected) {
    const auto counts = countsPerFrame(graph);
    for (const auto& [name, c] : counts) {
        const auto it = expected.find(name);
        // Passes not listed dispatch once per frame and so need no barrier of their own.
        const PerFrame want = it != expected.end() ? it->second : PerFrame{1, 0};
        EXPECT_EQ(c.dispatches, want.dispatches) << graph << ": " << name;
        EXPECT_EQ(c.barriers, want.barriers) << graph << ": " << name;
    }
}

TEST(CliPassBarriers, EachDependentDispatchWaitsAndNoOtherDoes) {
    // ATrousNH, 5 full-screen levels: each reads the level before.
    expectCounts("peres_base.json", {{"dn", {5, 4}}});
    // BMFR: accumulate -> fit -> weighted sum -> second temporal blend, a chain (P5's stages).
    expectCounts("koskela_bmfr.json", {{"bmfr", {4, 3}}});
    // SVGF: reprojection -> variance -> 5 a-trous levels, a chain.
    expectCounts("svgf.json", {{"svgf", {7, 6}}});
    // Unwarp: 3 lookup steps (the 2nd reads its group counts from the 1st), 3 phi mips each
    // reading the last, the coarse map (reads no mip: no barrier after the last mip), the fine
    // map (rewrites the coarse map's pixels), the two blur passes: every dispatch but the first
    // and the coarse map waits.
    expectCounts("koskela_vp_bmfr.json", {{"bmfr", {4, 3}}, {"un", {10, 8}}});
    // NH3LD: PathTrace clears then traces its sample list. ATrousNH builds the tile lists (3
    // steps), resets the fill counters (independent of the lists: no barrier), then runs the
    // main levels over the tile lists and the fill levels and copy back, each behind the
    // fill_args step that writes its group counts: every dispatch but the first and the counter
    // reset waits.
    expectCounts("peres_nh3ld.json", {{"pt", {2, 1}}, {"dn", {21, 19}}});
}

}  // namespace
