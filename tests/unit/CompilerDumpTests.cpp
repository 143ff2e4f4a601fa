// Plan dumps (core/graph/PlanDump.cpp): text and JSON, as `fovea validate --dump` prints them.
// CPU only.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "tests/unit/CompilerTestUtil.h"

using namespace fovea;
using namespace fovea::graph;
using namespace fovea::compilertest;

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
