// Pass plugins (`--plugin`, FOVEA_PLUGIN_PATH; docs/plugins.md): the example's Invert plugin runs,
// validates and documents like a built-in pass from every subcommand, and each kind of bad
// plugin is refused with exit 2 naming the file. The plugins are built by tests/CMakeLists.txt.
#include "tests/cli/CliTestUtil.h"

namespace fovea::clitest {
namespace {

// tests/CMakeLists.txt builds them into <build>/tests/plugins/<kind>/ (fovea is <build>/fovea).
const fs::path kPlugins = fs::path(FOVEA_EXE).parent_path() / "tests" / "plugins";
const fs::path kInvert = kPlugins / "invert" / "fovea_invert.so";
const fs::path kInvertGraph = kRepo / "examples" / "custom_pass" / "invert.json";

// Sets FOVEA_PLUGIN_PATH for the CLI runs of one test (each test is its own process).
class PluginPathEnv {
public:
    explicit PluginPathEnv(const std::string& value) {
        setenv("FOVEA_PLUGIN_PATH", value.c_str(), 1);
    }
    ~PluginPathEnv() { unsetenv("FOVEA_PLUGIN_PATH"); }
};

TEST(CliPlugin, RunsAPluginPassAndReadsItsShaderBesideTheLibrary) {
    ASSERT_TRUE(fs::exists(kInvert)) << kInvert;
    TempDir out;
    const Result r = cli(
        {"run", kInvertGraph.string(), "--plugin", kInvert.string(), "--out", out.path().string()});
    ASSERT_EQ(r.code, 0) << r.describe();
    const std::vector<float> px = pixels(out / "inv.result.exr");
    ASSERT_EQ(px.size(), 16u * 8u * 4u);
    const float expected[3] = {1.75f, 1.5f, 1.25f};  // white 2 - (0.25, 0.5, 0.75)
    for (size_t i = 0; i < px.size(); i += 4)
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(px[i + c], expected[c], 1e-6f) << i;
    // The report says which plugin a pass came from.
    EXPECT_TRUE(contains(readText(out / "report.json"), "fovea_invert.so"));
}

TEST(CliPlugin, EverySubcommandKnowsThePluginTypes) {
    // Without the plugin the type is unknown, and the message says how to load one.
    expectInputError(cli({"validate", kInvertGraph.string()}),
                     {"invert.json", "/passes/1/type", "unknown pass type 'Invert'", "--plugin"});
    const Result valid = cli({"validate", kInvertGraph.string(), "--plugin", kInvert.string()});
    EXPECT_EQ(valid.code, 0) << valid.describe();
    const Result listed = cli({"passes", "Invert", "--json", "--plugin", kInvert.string()});
    ASSERT_EQ(listed.code, 0) << listed.describe();
    const json pass = json::parse(listed.out).at(0);
    EXPECT_EQ(pass["plugin"], fs::canonical(kInvert).string());
    EXPECT_EQ(pass["params"].at(0)["name"], "white");
    // Built-in types say they are none.
    const Result blit = cli({"passes", "Blit", "--json", "--plugin", kInvert.string()});
    ASSERT_EQ(blit.code, 0) << blit.describe();
    EXPECT_TRUE(json::parse(blit.out).at(0)["plugin"].is_null());
}

TEST(CliPlugin, PluginPathTakesFoldersAndFilesAndLoadsEachLibraryOnce) {
    {
        PluginPathEnv env(":" + kInvert.parent_path().string() + ":");
        const Result r = cli({"validate", kInvertGraph.string()});
        EXPECT_EQ(r.code, 0) << r.describe();
        // The same library by --plugin as well: loaded once, not a duplicate type.
        const Result twice = cli({"validate", kInvertGraph.string(), "--plugin", kInvert.string()});
        EXPECT_EQ(twice.code, 0) << twice.describe();
    }
    {
        PluginPathEnv env("/nonexistent/fovea-plugins");
        expectInputError(cli({"passes"}), {"FOVEA_PLUGIN_PATH", "/nonexistent/fovea-plugins"});
    }
}

TEST(CliPlugin, GeneratesThePluginsOwnDocs) {
    TempDir docs;
    const Result none = cli({"passes", "--plugins-only"});
    expectInputError(none, {"--plugins-only", "no plugin is loaded"});
    const Result write = cli({"passes", "--plugin", kInvert.string(), "--plugins-only",
                              "--update-docs", docs.path().string()});
    ASSERT_EQ(write.code, 0) << write.describe();
    const std::string page = readText(docs / "Invert.md");
    EXPECT_TRUE(contains(page, "# Invert")) << page;
    EXPECT_TRUE(contains(page, "| `white` |")) << page;
    EXPECT_FALSE(fs::exists(docs / "Blit.md"));  // only the plugin's types
    const Result check = cli({"passes", "--plugin", kInvert.string(), "--plugins-only",
                              "--check-docs", docs.path().string()});
    EXPECT_EQ(check.code, 0) << check.describe();
}

TEST(CliPlugin, RefusesBadPluginsNamingTheFile) {
    TempDir dir;
    const std::string missing = (dir / "nowhere.so").string();
    expectInputError(cli({"passes", "--plugin", missing}),
                     {missing, "plugin not found", "--plugin"});
    const fs::path text = dir / "notes.so";
    writeText(text, "not a library\n");
    expectInputError(cli({"passes", "--plugin", text.string()}),
                     {text.string(), "not a shared library"});
    const std::string wrongAbi = (kPlugins / "wrong_abi" / "wrong_abi.so").string();
    expectInputError(cli({"validate", kInvertGraph.string(), "--plugin", wrongAbi}),
                     {wrongAbi, "fovea 0.0.1 plugin-abi 0", "rebuild it"});
    const std::string noEntry = (kPlugins / "no_entry" / "no_entry.so").string();
    expectInputError(cli({"passes", "--plugin", noEntry}),
                     {noEntry, "not a fovea pass plugin", "fovea_plugin_abi"});
    const std::string undefinedSymbol =
        (kPlugins / "undefined_symbol" / "undefined_symbol.so").string();
    expectInputError(cli({"run", kInvertGraph.string(), "--plugin", undefinedSymbol}),
                     {undefinedSymbol, "cannot load plugin", "fovea_symbol_nobody_defines"});
    // The same pass type from a second library (a copy under another name) is refused.
    const fs::path copy = dir / "invert_copy.so";
    fs::copy_file(kInvert, copy);
    expectInputError(cli({"passes", "--plugin", kInvert.string(), "--plugin", copy.string()}),
                     {copy.string(), "pass type 'Invert', which already exists",
                      fs::canonical(kInvert).string()});
}

}  // namespace
}  // namespace fovea::clitest
