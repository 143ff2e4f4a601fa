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

TEST(CliPassBarriers, ProfileDispatchesSplitsEachPassByDispatch) {
    // run --profile-dispatches: report.json's dispatch_gpu_ms times every dispatch, keyed by
    // shader and occurrence; Base's ATrousNH shows its five levels, each in every frame, and
    // their fastest runs together take no longer than the pass's slowest frame (the pass's
    // timestamps enclose its dispatches).
    TempDir tmp;
    const Result r = runSmall(kRepo / "graphs" / "peres_base.json", tmp / "out",
                              {"--save-frames", "none", "--profile-dispatches"});
    ASSERT_EQ(r.code, 0) << r.describe();
    const json report = readReport(tmp / "out");
    const json& p = passNamed(report, "dn");
    const json& split = p.at("dispatch_gpu_ms");
    ASSERT_EQ(split.size(), 5u) << split.dump();
    double sum = 0.0;
    for (uint32_t i = 0; i < 5; ++i) {
        EXPECT_EQ(split[i].at("shader"), "atrous_nh/atrous_nh.comp");
        EXPECT_EQ(split[i].at("occurrence"), i);
        EXPECT_EQ(split[i].at("runs"), 2);
        EXPECT_GE(split[i].at("ms").at("median").get<double>(), 0.0);
        sum += split[i].at("ms").at("min").get<double>();
    }
    EXPECT_GT(sum, 0.0);
    EXPECT_LE(sum, p.at("gpu_ms").at("max").get<double>());
    // Without the flag there is no split (and no timestamps between dispatches).
    TempDir plain;
    const Result q =
        runSmall(kRepo / "graphs" / "peres_base.json", plain / "out", {"--save-frames", "none"});
    ASSERT_EQ(q.code, 0) << q.describe();
    for (const auto& p : readReport(plain / "out").at("passes"))
        EXPECT_FALSE(p.contains("dispatch_gpu_ms")) << p.at("name");
}

}  // namespace
