// The P2 setting benches (graphs/benches/p2_*.json, issue 34: P2's Table 2 in its own setting)
// run end to end at a tiny size: each shipped file, shrunk to 32 px, 2 frames and a 2-spp
// reference, gives finite errors for its three rows, and the two BMFR rows (published and fovea
// variant) differ, so the variant reaches the pass. The full-size figures are benchmarks
// (docs/benchmarks.md), not tests.
#include <algorithm>
#include <cmath>

#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

// The shipped bench with absolute paths (it is written elsewhere) and a tiny workload.
json tinyP2Bench(const fs::path& file) {
    json spec = json::parse(readText(file));
    const fs::path dir = file.parent_path();
    auto absolute = [&](const std::string& p) {
        return p.rfind("builtin:", 0) == 0 ? p : (dir / p).lexically_normal().string();
    };
    spec["scene"] = absolute(spec.at("scene"));
    spec["camera"] = absolute(spec.at("camera"));
    for (auto& g : spec["graphs"]) g["file"] = absolute(g.at("file"));
    const auto size = spec.at("size");
    const int width = 32, height = std::max(8, 32 * size[1].get<int>() / size[0].get<int>());
    spec["size"] = {width, height};
    spec["frames"] = 2;
    spec["warmup"] = std::min(spec.value("warmup", 1), 1);
    spec["reference"]["render"]["spp"] = 2;
    return spec;
}

}  // namespace

TEST(CliBenchP2, SettingBenchesRunAtATinySize) {
    TempDir tmp;
    size_t count = 0;
    for (const auto& e : fs::directory_iterator(kRepo / "graphs" / "benches")) {
        const std::string name = e.path().filename().string();
        if (name.rfind("p2_", 0) != 0 || e.path().extension() != ".json") continue;
        ++count;
        const fs::path file = tmp / name;
        writeText(file, tinyP2Bench(e.path()).dump(2));
        const fs::path out = tmp / e.path().stem();
        Result r = cli({"bench", file.string(), "--out", out.string(), "--quiet"});
        ASSERT_EQ(r.code, 0) << name << "\n" << r.describe();
        const json result = json::parse(readText(out / "bench.json"));
        const auto& graphs = result.at("graphs");
        ASSERT_EQ(graphs.size(), 3u) << name;
        for (const auto& g : graphs) {
            const double rmse = g.at("errors").at("mean").at("rmse");
            EXPECT_TRUE(std::isfinite(rmse) && rmse > 0.0) << name << " " << g.at("label");
        }
        EXPECT_EQ(graphs[0].at("label"), "BMFR published+TAA") << name;
        EXPECT_EQ(graphs[1].at("label"), "BMFR fovea+TAA") << name;
        EXPECT_NE(graphs[0].at("errors").at("mean").at("rmse").get<double>(),
                  graphs[1].at("errors").at("mean").at("rmse").get<double>())
            << name << ": the BMFR variant changed nothing";
    }
    EXPECT_GE(count, 8u);  // 3 Table-2 settings + 5 one-factor benches
}
