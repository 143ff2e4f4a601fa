// Every graph in tests/graph/bad/compile/ parses but must fail to compile (with the built-in
// passes) with an InputError whose message names the file and contains the fragment in the
// NAME.expect sidecar. CPU-only: the compile stages need no GPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/graph/CompilerStages.h"
#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/util/Error.h"
#include "passes/RegisterPasses.h"

namespace fs = std::filesystem;
using namespace fovea;
using namespace fovea::graph;

namespace {

const fs::path kDir = fs::path(FOVEA_TEST_DIR) / "graph" / "bad" / "compile";

// Files detected only when the graph is built on a GPU. None since bypass pairs are checked in
// the compile stages (bypass_size_mismatch.json is now an ordinary member of the loop).
const std::set<std::string> kGpuOnly = {};

CompileOptions options64x64() {
    CompileOptions o;
    o.width = 64;
    o.height = 64;
    return o;
}

std::string readExpect(const fs::path& path) {
    std::ifstream stream(path, std::ios::binary);
    std::stringstream buffer;
    buffer << stream.rdbuf();
    std::string text = buffer.str();
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r' || text.back() == ' '))
        text.pop_back();
    return text;
}

std::vector<fs::path> files(const std::string& extension) {
    std::vector<fs::path> out;
    for (const auto& entry : fs::directory_iterator(kDir))
        if (entry.path().extension() == extension) out.push_back(entry.path());
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

TEST(BadGraphCompile, EveryFileHasAnExpectation) {
    std::vector<fs::path> graphs = files(".json"), expects = files(".expect");
    ASSERT_GE(graphs.size(), 15u) << kDir;
    EXPECT_EQ(graphs.size(), expects.size());
    for (const auto& g : graphs) {
        fs::path e = fs::path(g).replace_extension(".expect");
        ASSERT_TRUE(fs::exists(e)) << e;
        EXPECT_FALSE(readExpect(e).empty()) << e;
    }
    for (const auto& e : expects)
        EXPECT_TRUE(fs::exists(fs::path(e).replace_extension(".json"))) << e;
}

TEST(BadGraphCompile, EveryFileFailsWithItsMessage) {
    registerBuiltinPasses();
    int checked = 0;
    for (const fs::path& path : files(".json")) {
        const std::string name = path.filename().string();
        if (kGpuOnly.count(name)) continue;
        SCOPED_TRACE(name);
        const std::string fragment = readExpect(fs::path(path).replace_extension(".expect"));
        GraphDesc desc;
        try {
            desc = parseGraphFile(path);
        } catch (const InputError& e) {
            ADD_FAILURE() << "bad compile graph does not even parse: " << e.what();
            continue;
        }
        try {
            compileGraphPlan(desc, passRegistry(), options64x64());
            ADD_FAILURE() << "compiled without error; expected: " << fragment;
        } catch (const InputError& e) {
            std::string what = e.what();
            EXPECT_NE(what.find(fragment), std::string::npos)
                << "expected fragment: " << fragment << "\n              got: " << what;
            // The message starts with the file as given, then the pointer.
            EXPECT_EQ(what.rfind(path.string() + ": ", 0), 0u) << what;
            EXPECT_NE(what.find(name), std::string::npos) << what;
            EXPECT_EQ(e.file(), path.string());
        }
        ++checked;
    }
    EXPECT_GE(checked, 15);
}

TEST(BadGraphCompile, GpuOnlyFilesCompileOnTheCpu) {
    // The files left to the GPU test really are accepted by the compile stages (otherwise they
    // belong in the loop above).
    registerBuiltinPasses();
    for (const std::string& name : kGpuOnly) {
        SCOPED_TRACE(name);
        ASSERT_TRUE(fs::exists(kDir / name));
        GraphDesc desc = parseGraphFile(kDir / name);
        EXPECT_NO_THROW(compileGraphPlan(desc, passRegistry(), options64x64()));
    }
}
