// The map of the house (docs/architecture.md, README's layout) names only paths that exist, and
// docs and code cite the source documents through docs/references.md, never the design notes'
// or documents' paths outside the repository (issue 30: "a page of the house map names a path that
// does not exist").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
const fs::path kRepo = fs::path(FOVEA_TEST_DIR).parent_path();

std::string readDoc(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// Repository paths a page names: `backticked` ones under a top-level folder, and the first word
// of each line of README's layout block.
std::vector<std::string> namedPaths(const std::string& text) {
    static const std::regex top(
        "^(core|passes|shaders|eval|apps|editor|tests|graphs|docs|scripts|examples|cmake)/");
    std::vector<std::string> out;
    static const std::regex ticked("`([A-Za-z0-9_./*<>{},-]+)`");
    for (std::sregex_iterator it(text.begin(), text.end(), ticked), end; it != end; ++it)
        if (std::regex_search((*it)[1].str(), top)) out.push_back((*it)[1].str());
    const size_t layout = text.find("## Repository layout");
    if (layout != std::string::npos) {
        std::istringstream lines(text.substr(layout, text.find("\n## ", layout + 1) - layout));
        for (std::string line, word; std::getline(lines, line);) {
            std::istringstream words(line);
            if (words >> word && std::regex_search(word, top)) out.push_back(word);
        }
    }
    return out;
}

TEST(DocsMap, PathsNamedInTheMapExist) {
    size_t checked = 0;
    for (const char* page : {"docs/architecture.md", "README.md"}) {
        const std::string text = readDoc(kRepo / page);
        ASSERT_FALSE(text.empty()) << page;
        for (const std::string& path : namedPaths(text)) {
            // Patterns (passes/<Name>/, Compiler*Tests.cpp, {h,cpp}) name no one file; the
            // "how to write a pass" walk-through names the Scale pass the reader creates.
            if (path.find_first_of("<*{") != std::string::npos) continue;
            if (path.find("Scale") != std::string::npos ||
                path.find("/scale/") != std::string::npos)
                continue;
            ++checked;
            EXPECT_TRUE(fs::exists(kRepo / path))
                << page << " names '" << path << "', which does not exist";
        }
    }
    EXPECT_GE(checked, 30u);  // the extraction itself still works
}

TEST(DocsMap, DocsCiteNoPathOutsideTheRepository) {
    // The design notes and the documents' texts live beside the repository, not in it: docs and
    // code cite the documents (docs/references.md). Scene files under ../shared/scenes are user
    // data that commands and tests may name.
    for (const char* root : {"docs", "core", "passes", "eval", "apps", "editor", "shaders"})
        for (const auto& entry : fs::recursive_directory_iterator(kRepo / root)) {
            if (!entry.is_regular_file()) continue;
            const std::string text = readDoc(entry.path());
            for (const char* outside : {"shared/design/", "shared/seeds/"})
                EXPECT_EQ(text.find(outside), std::string::npos)
                    << entry.path() << " names " << outside << " (cite docs/references.md)";
        }
    const std::string glossary = readDoc(kRepo / "docs" / "references.md");
    for (const char* name :
         {"seed 000", "seed 003", "seed 004", "**P1**", "**P2**", "**P3**", "**P4**", "**P5**"})
        EXPECT_NE(glossary.find(name), std::string::npos) << name;
}

}  // namespace
