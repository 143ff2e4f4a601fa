// Graph file parsing (core/graph/GraphDesc*) and the JSON helpers under it (core/util/JsonUtil).
// Every bad-input class has a file in tests/graph/bad/parse/ with a NAME.expect sidecar holding
// the message fragment; BadGraphFiles checks them all.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/graph/GraphDesc.h"
#include "core/util/Error.h"
#include "core/util/JsonUtil.h"
#include "tests/unit/InputErrorOf.h"

namespace fs = std::filesystem;
using namespace fovea;
using namespace fovea::graph;

using fovea::test::inputErrorOf;

namespace {

const char* kFullGraph = R"({
  "version": 1,
  "name": "demo",
  "description": "every field of the format",
  "defaults": { "size": [320, 240], "frames": 4, "seed": 18446744073709551615, "scene": "cornell" },
  "passes": [
    { "name": "src", "type": "ImageSource", "params": { "pattern": "gradient", "scale": 0.5 } },
    { "name": "acc", "type": "Accumulate", "enabled": false },
    { "name": "tm", "type": "Tonemap", "params": {} }
  ],
  "edges": [
    { "from": "src.color", "to": "acc.input" },
    { "from": "acc.color", "to": "acc.history", "delay": 1 },
    { "from": "acc.color", "to": "tm.input", "delay": 0 }
  ],
  "order": [ { "before": "src", "after": "tm" } ],
  "outputs": [ "tm.output", { "source": "acc.color" } ],
  "editor": { "nodes": { "src": [10, 20] }, "zoom": 1.5 }
})";

std::string readText(const fs::path& path) {
    std::ifstream stream(path, std::ios::binary);
    std::stringstream buffer;
    buffer << stream.rdbuf();
    return buffer.str();
}

// A fresh directory per test so saves never collide between runs or parallel ctest jobs.
class TempDir {
public:
    TempDir() {
        const testing::TestInfo* info = testing::UnitTest::GetInstance()->current_test_info();
        mPath = fs::temp_directory_path() /
                ("fovea_graphdesc_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
        fs::remove_all(mPath);
        fs::create_directories(mPath);
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(mPath, ignored);
    }
    const fs::path& path() const { return mPath; }

private:
    fs::path mPath;
};

}  // namespace

TEST(GraphDesc, ParsesEveryField) {
    GraphDesc g = parseGraphText(kFullGraph, "full.json");
    EXPECT_EQ(g.version, 1);
    EXPECT_EQ(g.name, "demo");
    EXPECT_EQ(g.description, "every field of the format");
    EXPECT_EQ(g.file, "full.json");
    ASSERT_TRUE(g.defaults.size.has_value());
    EXPECT_EQ((*g.defaults.size)[0], 320u);
    EXPECT_EQ((*g.defaults.size)[1], 240u);
    EXPECT_EQ(g.defaults.frames, 4u);
    EXPECT_EQ(g.defaults.seed, 18446744073709551615ull);
    EXPECT_EQ(g.defaults.scene, "cornell");

    ASSERT_EQ(g.passes.size(), 3u);
    EXPECT_EQ(g.passes[0].name, "src");
    EXPECT_EQ(g.passes[0].type, "ImageSource");
    EXPECT_EQ(g.passes[0].params.at("pattern"), "gradient");
    EXPECT_DOUBLE_EQ(g.passes[0].params.at("scale").get<double>(), 0.5);
    EXPECT_TRUE(g.passes[0].enabled);
    EXPECT_EQ(g.passes[0].pointer, "/passes/0");
    EXPECT_FALSE(g.passes[1].enabled);
    EXPECT_TRUE(g.passes[1].params.is_object());
    EXPECT_TRUE(g.passes[1].params.empty());
    EXPECT_EQ(g.passes[2].pointer, "/passes/2");

    ASSERT_EQ(g.edges.size(), 3u);
    EXPECT_EQ(g.edges[0].from.pass, "src");
    EXPECT_EQ(g.edges[0].from.field, "color");
    EXPECT_EQ(g.edges[0].to.str(), "acc.input");
    EXPECT_EQ(g.edges[0].delay, 0u);
    EXPECT_EQ(g.edges[1].delay, 1u);
    EXPECT_EQ(g.edges[1].pointer, "/edges/1");

    ASSERT_EQ(g.order.size(), 1u);
    EXPECT_EQ(g.order[0].before, "src");
    EXPECT_EQ(g.order[0].after, "tm");
    EXPECT_EQ(g.order[0].pointer, "/order/0");

    ASSERT_EQ(g.outputs.size(), 2u);
    EXPECT_EQ(g.outputs[0].source.str(), "tm.output");
    EXPECT_EQ(g.outputs[1].source.str(), "acc.color");
    EXPECT_EQ(g.outputs[1].pointer, "/outputs/1");

    EXPECT_EQ(g.editor.at("zoom"), 1.5);

    ASSERT_NE(g.findPass("acc"), nullptr);
    EXPECT_EQ(g.findPass("acc")->type, "Accumulate");
    EXPECT_EQ(g.findPass("nope"), nullptr);
    EXPECT_EQ(g.passNames(), (std::vector<std::string>{"src", "acc", "tm"}));
}

TEST(GraphDesc, MinimalGraphGetsDefaults) {
    GraphDesc g = parseGraphText(R"({"version": 1, "passes": [{"name": "a", "type": "T"}]})", "m");
    EXPECT_EQ(g.name, "");
    EXPECT_FALSE(g.defaults.size || g.defaults.frames || g.defaults.seed || g.defaults.scene);
    EXPECT_TRUE(g.passes[0].params.is_object());
    EXPECT_TRUE(g.edges.empty() && g.order.empty() && g.outputs.empty());
    EXPECT_TRUE(g.editor.is_null());
}

TEST(GraphDesc, CanonicalFormOmitsDefaultsAndRoundTrips) {
    GraphDesc g = parseGraphText(kFullGraph, "full.json");
    nlohmann::json j = graphToJson(g);
    EXPECT_FALSE(j["passes"][1].contains("params"));  // empty params omitted
    EXPECT_FALSE(j["passes"][2].contains("params"));
    EXPECT_EQ(j["passes"][1]["enabled"], false);
    EXPECT_FALSE(j["passes"][0].contains("enabled"));  // true is the default
    EXPECT_FALSE(j["edges"][2].contains("delay"));     // 0 is the default
    EXPECT_EQ(j["outputs"][1], "acc.color");           // object form saved as the short string
    EXPECT_EQ(j["editor"], g.editor);
    EXPECT_EQ(parseGraphJson(j, "again"), g);
    EXPECT_EQ(parseGraphText(graphToText(g), "again"), g);

    // Key order is fixed: the text form reads version, name, ..., editor.
    std::string text = graphToText(g);
    EXPECT_LT(text.find("\"version\""), text.find("\"name\""));
    EXPECT_LT(text.find("\"passes\""), text.find("\"edges\""));
    EXPECT_LT(text.find("\"outputs\""), text.find("\"editor\""));
    EXPECT_EQ(text.back(), '\n');

    GraphDesc minimal = parseGraphText(R"({"version":1,"passes":[{"name":"a","type":"T"}]})", "m");
    EXPECT_EQ(graphToJson(minimal),
              nlohmann::json::parse(R"({"version":1,"passes":[{"name":"a","type":"T"}]})"));
}

TEST(GraphDesc, EqualityIgnoresProvenance) {
    GraphDesc parsed = parseGraphText(kFullGraph, "full.json");
    GraphDesc copy = parsed;
    copy.file = "elsewhere.json";
    copy.passes[0].pointer.clear();
    EXPECT_EQ(copy, parsed);
    copy.passes[0].params["pattern"] = "checker";
    EXPECT_NE(copy, parsed);
}

TEST(GraphDesc, SaveRoundTripsAndRefusesToOverwrite) {
    TempDir dir;
    fs::path path = dir.path() / "saved.json";
    GraphDesc g = parseGraphText(kFullGraph, "full.json");
    saveGraphFile(g, path, false);
    GraphDesc loaded = parseGraphFile(path);
    EXPECT_EQ(loaded, g);
    EXPECT_EQ(loaded.file, path.string());
    EXPECT_EQ(readText(path), graphToText(g));

    std::string message = inputErrorOf([&] { saveGraphFile(g, path, false); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("already exists"), std::string::npos) << message;

    GraphDesc changed = g;
    changed.name = "changed";
    saveGraphFile(changed, path, true);
    EXPECT_EQ(parseGraphFile(path).name, "changed");
    EXPECT_FALSE(fs::exists(path.string() + ".tmp"));
}

TEST(GraphDesc, SaveRefusesAnInvalidGraph) {
    TempDir dir;
    fs::path path = dir.path() / "bad.json";
    GraphDesc g;
    PassDesc pass;
    pass.name = "a";
    pass.type = "T";
    g.passes.push_back(pass);
    EdgeDesc edge;
    edge.from = {"a", "out"};
    edge.to = {"missing", "in"};
    g.edges.push_back(edge);
    std::string message = inputErrorOf([&] { saveGraphFile(g, path, false); });
    EXPECT_NE(message.find("/edges/0/to: unknown pass 'missing'"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(path));
}

TEST(GraphDesc, NonexistentFile) {
    std::string path = std::string(FOVEA_TEST_DIR) + "/graph/bad/parse/does_not_exist.json";
    std::string message = inputErrorOf([&] { parseGraphFile(path); });
    EXPECT_EQ(message, path + ": cannot read file: file not found");
}

TEST(GraphDesc, DirectoryIsNotAFile) {
    std::string path = std::string(FOVEA_TEST_DIR) + "/graph/bad/parse";
    std::string message = inputErrorOf([&] { parseGraphFile(path); });
    EXPECT_NE(message.find("cannot read file: "), std::string::npos) << message;
}

TEST(GraphDesc, SyntaxErrorLineAndColumn) {
    const char* text = "{\n  \"version\": 1,\n  \"passes\": [ , ]\n}\n";
    std::string message = inputErrorOf([&] { parseGraphText(text, "g.json"); });
    EXPECT_EQ(message.rfind("g.json: line 3, column 15: JSON syntax error", 0), 0u) << message;
    EXPECT_EQ(message.find("syntax error while parsing"), std::string::npos) << message;
}

// Every tests/graph/bad/parse/NAME.json must fail with its NAME.expect fragment, and the message
// must name the file (users run several graphs in one go).
TEST(GraphDesc, BadGraphFiles) {
    fs::path dir = fs::path(FOVEA_TEST_DIR) / "graph" / "bad" / "parse";
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() == ".json") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    EXPECT_GE(files.size(), 18u);
    for (const fs::path& file : files) {
        SCOPED_TRACE(file.filename().string());
        fs::path expectPath = fs::path(file).replace_extension(".expect");
        ASSERT_TRUE(fs::exists(expectPath)) << "missing " << expectPath;
        std::string expected = readText(expectPath);
        while (!expected.empty() && (expected.back() == '\n' || expected.back() == '\r')) {
            expected.pop_back();
        }
        ASSERT_FALSE(expected.empty());
        std::string message = inputErrorOf([&] { parseGraphFile(file); });
        EXPECT_NE(message.find(expected), std::string::npos)
            << "message:  " << message << "\nexpected: " << expected;
        EXPECT_NE(message.find(file.filename().string()), std::string::npos) << message;
    }
}

TEST(GraphDesc, Endpoints) {
    EXPECT_EQ(parseEndpoint("tm.input"), (Endpoint{"tm", "input"}));
    EXPECT_EQ(parseEndpoint("_a1.b_2")->str(), "_a1.b_2");
    for (const char* bad : {"tm", "tm.", ".input", "tm.a.b", "1tm.x", "t-m.x", "tm.in put", ""}) {
        EXPECT_FALSE(parseEndpoint(bad).has_value()) << bad;
    }
    EXPECT_TRUE(isValidPassName("Tone_map2"));
    EXPECT_FALSE(isValidPassName("2d"));
}

TEST(JsonUtil, TextPosition) {
    std::string text = "ab\ncd\n\nef";
    EXPECT_EQ(textPosition(text, 0).line, 1u);
    EXPECT_EQ(textPosition(text, 1).column, 2u);
    EXPECT_EQ(textPosition(text, 2).column, 3u);  // the newline itself ends line 1
    EXPECT_EQ(textPosition(text, 3).line, 2u);
    EXPECT_EQ(textPosition(text, 3).column, 1u);
    EXPECT_EQ(textPosition(text, 7).line, 4u);
    EXPECT_EQ(textPosition(text, 100).column, 3u);  // clamped: just after "ef"
}

TEST(JsonUtil, PointerEscaping) {
    EXPECT_EQ(jsonPointerEscape("a/b~c"), "a~1b~0c");
    EXPECT_EQ(jsonPointerAppend(jsonPointerAppend("", "passes"), 3), "/passes/3");
    EXPECT_EQ(jsonPointerAppend("/passes/3/params", "spp"), "/passes/3/params/spp");
    // Duplicate keys deep inside params are reported with an escaped pointer.
    const char* text = R"({"version": 1, "passes": [{"name": "a", "type": "T",
                          "params": {"x/y": [0, {"k": 1, "k": 2}]}}]})";
    EXPECT_EQ(inputErrorOf([&] { parseGraphText(text, "f.json"); }),
              "f.json: /passes/0/params/x~1y/1: duplicate key 'k'");
}

TEST(JsonUtil, TypedGetters) {
    nlohmann::json j = nlohmann::json::parse(
        R"({"s": "x", "i": -3, "u": 18446744073709551615, "f": 2.5, "b": true, "list": [1]})");
    JsonNode root(j, "f.json", "/p");
    EXPECT_EQ(root.require("s").asString(), "x");
    EXPECT_EQ(root.require("i").asInt(), -3);
    EXPECT_EQ(root.require("u").asUnsigned(), 18446744073709551615ull);
    EXPECT_DOUBLE_EQ(root.require("f").asNumber(), 2.5);
    EXPECT_TRUE(root.require("b").asBool());
    EXPECT_EQ(root.require("list").at(0).pointer(), "/p/list/0");
    EXPECT_FALSE(root.find("zz").has_value());

    EXPECT_EQ(inputErrorOf([&] { root.require("s").asInt(); }),
              "f.json: /p/s: expected an integer, got string");
    EXPECT_EQ(inputErrorOf([&] { root.require("u").asInt(); }),
              "f.json: /p/u: out of range: 18446744073709551615 (allowed "
              "-9223372036854775808..9223372036854775807)");
    EXPECT_EQ(inputErrorOf([&] { root.require("i").asUnsigned(); }),
              "f.json: /p/i: expected a non-negative integer, got -3");
    EXPECT_EQ(inputErrorOf([&] { root.require("b").asNumber(); }),
              "f.json: /p/b: expected a number, got boolean");
    EXPECT_EQ(inputErrorOf([&] { root.require("zz"); }), "f.json: /p: missing required field 'zz'");
    EXPECT_EQ(inputErrorOf([&] {
                  root.checkFields({"s", "i", "u", "f", "b"});
              }),
              "f.json: /p: unknown field 'list'");
    EXPECT_EQ(inputErrorOf([&] { root.require("list").find("x"); }),
              "f.json: /p/list: expected an object, got array");
}

TEST(GraphDesc, DefaultCameraNeedsADefaultScene) {
    // Issue 33, class 6: without a default scene, defaults.camera was never used, so any text
    // (even "/etc/passwd") passed; it is an error at its pointer now.
    const std::string head = R"({"version": 1, "name": "g", "passes": [{"name": "src",
        "type": "ImageSource"}], "outputs": ["src.color"], "defaults": )";
    for (const std::string& defaults :
         {std::string(R"({"camera": "/etc/passwd"})"),
          std::string(R"({"scene": "none", "camera": "path.json"})")}) {
        std::string message =
            inputErrorOf([&] { parseGraphText(head + defaults + "}", "g.json"); });
        EXPECT_NE(message.find("g.json: /defaults/camera: a default camera needs a default scene"),
                  std::string::npos)
            << message;
    }
    EXPECT_NO_THROW(parseGraphText(
        head + R"({"scene": "builtin:cornell", "camera": "path.json"})" + "}", "g.json"));
}
