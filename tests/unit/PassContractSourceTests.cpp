// The pass contract as the code keeps it (docs/architecture.md "The pass contract"): a pass
// records no barrier and dispatches only through its ExecuteContext, which derives the barriers
// between its dispatches (gpu::DispatchHazards). A pass that records its own barrier, or
// dispatches on a raw command buffer past the context, makes its work invisible to the derivation
// (and to report.json's `dispatches` / `barriers_in_pass`); this test names the file and line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
const fs::path kRepo = fs::path(FOVEA_TEST_DIR).parent_path();

// "file:line: text" for every line under passes/ matching `pattern` (comments skipped).
std::vector<std::string> linesMatching(const std::regex& pattern) {
    std::vector<std::string> out;
    for (const auto& entry : fs::recursive_directory_iterator(kRepo / "passes")) {
        const auto ext = entry.path().extension();
        if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".h")) continue;
        std::ifstream in(entry.path());
        int number = 0;
        for (std::string line; std::getline(in, line);) {
            ++number;
            const auto code = line.substr(0, line.find("//"));
            if (std::regex_search(code, pattern))
                out.push_back(fs::relative(entry.path(), kRepo).string() + ":" +
                              std::to_string(number) + ": " + line);
        }
    }
    return out;
}

std::string join(const std::vector<std::string>& lines) {
    std::string text;
    for (const auto& l : lines) text += "\n  " + l;
    return text;
}

TEST(PassContractSource, PassesRecordNoBarriers) {
    const auto found = linesMatching(
        std::regex(R"(core/vk/Barriers\.h|[Bb]arrier2?\s*\(|pipelineBarrier|MemoryBarrier)"));
    EXPECT_TRUE(found.empty()) << "barriers recorded by a pass (dispatch through ctx.dispatch: "
                                  "the context derives them):"
                               << join(found);
}

TEST(PassContractSource, PassesDispatchThroughTheirContext) {
    // `x->dispatch(`, `x.dispatchIndirect(`, `cmd.dispatch(` ...: anything but `ctx.`.
    const std::regex call(R"((\w+)\s*(\.|->)\s*dispatch(Indirect)?\s*\()");
    std::vector<std::string> found;
    for (const auto& line : linesMatching(call)) {
        const auto code = line.substr(0, line.find("//", line.find(": ")));
        for (std::sregex_iterator it(code.begin(), code.end(), call), end; it != end; ++it)
            if ((*it)[1].str() != "ctx" || (*it)[2].str() != ".") found.push_back(line);
    }
    EXPECT_TRUE(found.empty()) << "dispatches past the ExecuteContext (use ctx.dispatch / "
                                  "ctx.dispatchIndirect):"
                               << join(found);
    // And the rule has something to check: the built-in passes do dispatch through ctx.
    EXPECT_GT(linesMatching(std::regex(R"(ctx\.dispatch(Indirect)?\()")).size(), 20u);
}

}  // namespace
