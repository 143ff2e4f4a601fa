// Pass parameters (core/graph/Param.cpp): defaults, JSON load with file + pointer errors, save,
// describe, and the text of `--set pass.param=value`. Uses the AllParams test pass (TestPasses.h).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/graph/Param.h"
#include "core/graph/PassRegistry.h"
#include "core/util/Error.h"
#include "passes/RegisterPasses.h"
#include "tests/passes/TestPasses.h"

using namespace fovea;
using namespace fovea::graph;
using nlohmann::json;
using testpasses::AllParams;

namespace {

const PassRegistry& registry() {
    static const PassRegistry r = testpasses::testRegistry();
    return r;
}

std::unique_ptr<AllParams> makePass() {
    std::unique_ptr<Pass> pass = registry().create("AllParams", "p");
    return std::unique_ptr<AllParams>(static_cast<AllParams*>(pass.release()));
}

void expectDefaults(const AllParams& p) {
    EXPECT_EQ(p.enabled, true);
    EXPECT_EQ(p.count, 3);
    EXPECT_EQ(p.big, 0);
    EXPECT_FLOAT_EQ(p.gain, 0.5f);
    EXPECT_FLOAT_EQ(p.freeFloat, 2.0f);
    EXPECT_EQ(p.mode, "fast");
    EXPECT_EQ(p.label, "none");
    EXPECT_EQ(p.tint, glm::vec3(1.0f, 0.5f, 0.25f));
}

// The message loadParams throws for `params`, or "<no error>".
std::string paramLoadError(const json& params) {
    auto pass = makePass();
    try {
        loadParams(*pass, params, "g.json", "/passes/0/params");
    } catch (const InputError& e) {
        return e.what();
    }
    return "<no error>";
}

constexpr const char* kPrefix = "g.json: /passes/0/params/";

}  // namespace

TEST(ParamDefaults, AppliedOnCreate) {
    auto pass = makePass();
    expectDefaults(*pass);
    EXPECT_EQ(pass->name(), "p");
    EXPECT_EQ(pass->type(), "AllParams");
}

TEST(ParamDefaults, ApplyResetsChangedValues) {
    auto pass = makePass();
    pass->count = 42;
    pass->mode = "off";
    pass->tint = glm::vec3(0.0f);
    applyParamDefaults(*pass);
    expectDefaults(*pass);
}

TEST(ParamDefaults, FilterStrength) {
    std::unique_ptr<Pass> pass = registry().create("Filter", "f");
    EXPECT_FLOAT_EQ(static_cast<testpasses::Filter&>(*pass).strength(), 1.0f);
}

TEST(ParamLoad, AcceptsValidValues) {
    auto pass = makePass();
    loadParams(*pass,
               {{"enabled", false},
                {"count", 100},
                {"big", -2000000000},
                {"gain", -1},  // an integer is a valid float
                {"free", 1e6},
                {"mode", "exact"},
                {"label", "anything at all"},
                {"tint", {0, 4, 2.5}}},
               "g.json", "/passes/0/params");
    EXPECT_EQ(pass->enabled, false);
    EXPECT_EQ(pass->count, 100);
    EXPECT_EQ(pass->big, -2000000000);
    EXPECT_FLOAT_EQ(pass->gain, -1.0f);
    EXPECT_FLOAT_EQ(pass->freeFloat, 1e6f);
    EXPECT_EQ(pass->mode, "exact");
    EXPECT_EQ(pass->label, "anything at all");
    EXPECT_EQ(pass->tint, glm::vec3(0.0f, 4.0f, 2.5f));
}

TEST(ParamLoad, EmptyObjectKeepsDefaults) {
    auto pass = makePass();
    loadParams(*pass, json::object(), "g.json", "/passes/0/params");
    expectDefaults(*pass);
    // A partial object changes only what it names.
    loadParams(*pass, {{"count", 0}}, "g.json", "/passes/0/params");
    EXPECT_EQ(pass->count, 0);
    EXPECT_EQ(pass->mode, "fast");
}

TEST(ParamLoad, RejectsNonObject) {
    EXPECT_EQ(paramLoadError(json::array({1})),
              "g.json: /passes/0/params: expected an object of parameters, got array");
    EXPECT_EQ(paramLoadError(json(3)),
              "g.json: /passes/0/params: expected an object of parameters, got integer");
}

TEST(ParamLoad, RejectsUnknownWithDidYouMean) {
    EXPECT_EQ(paramLoadError({{"cuont", 1}}),
              std::string(kPrefix) + "cuont: unknown parameter 'cuont' (did you mean 'count'?)");
    // Nothing close: list the parameters instead.
    EXPECT_EQ(paramLoadError({{"zzzzzzzzzz", 1}}),
              std::string(kPrefix) +
                  "zzzzzzzzzz: unknown parameter 'zzzzzzzzzz' (parameters: enabled, count, big, "
                  "gain, free, mode, label, tint)");
}

TEST(ParamLoad, ErrorCarriesFileAndPointer) {
    auto pass = makePass();
    try {
        loadParams(*pass, {{"count", 1000}}, "g.json", "/passes/3/params");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "g.json");
        EXPECT_EQ(e.pointer(), "/passes/3/params/count");
    }
}

TEST(ParamLoad, RejectsWrongType) {
    std::string p = kPrefix;
    EXPECT_EQ(paramLoadError({{"enabled", 1}}), p + "enabled: expected a boolean, got integer 1");
    EXPECT_EQ(paramLoadError({{"enabled", "true"}}),
              p + "enabled: expected a boolean, got string \"true\"");
    EXPECT_EQ(paramLoadError({{"count", 1.5}}), p + "count: expected an integer, got number 1.5");
    EXPECT_EQ(paramLoadError({{"count", "3"}}), p + "count: expected an integer, got string \"3\"");
    EXPECT_EQ(paramLoadError({{"gain", "high"}}),
              p + "gain: expected a number, got string \"high\"");
    EXPECT_EQ(paramLoadError({{"gain", nullptr}}).find(p + "gain: expected a number, got null"),
              0u);
    EXPECT_EQ(paramLoadError({{"mode", 3}}), p + "mode: expected a string, got integer 3");
    EXPECT_EQ(paramLoadError({{"tint", {1, 2}}}),
              p + "tint: expected an array of 3 numbers, got array [1,2]");
    EXPECT_EQ(paramLoadError({{"tint", 1}}),
              p + "tint: expected an array of 3 numbers, got integer 1");
    EXPECT_EQ(paramLoadError({{"tint", {1, "x", 2}}}),
              p + "tint/1: expected a number, got string \"x\"");
    // Long values are shortened in the message.
    std::string msg = paramLoadError({{"count", std::string(100, 'a')}});
    EXPECT_NE(msg.find("got string \"aaaa"), std::string::npos) << msg;
    EXPECT_NE(msg.find("..."), std::string::npos) << msg;
    EXPECT_LT(msg.size(), 120u) << msg;
}

TEST(ParamLoad, RejectsOutOfRange) {
    std::string p = kPrefix;
    EXPECT_EQ(paramLoadError({{"count", 101}}), p + "count: out of range: 101 (allowed 0..100)");
    EXPECT_EQ(paramLoadError({{"count", -1}}), p + "count: out of range: -1 (allowed 0..100)");
    EXPECT_EQ(paramLoadError({{"gain", 1.5}}), p + "gain: out of range: 1.5 (allowed -1..1)");
    EXPECT_EQ(paramLoadError({{"tint", {0, 5, 0}}}), p + "tint: out of range: 5 (allowed 0..4)");
    EXPECT_EQ(paramLoadError({{"tint", {0, 0, -0.5}}}),
              p + "tint: out of range: -0.5 (allowed 0..4)");
    // The range is inclusive.
    EXPECT_EQ(paramLoadError({{"count", 0}, {"gain", 1.0}, {"tint", {4, 4, 4}}}), "<no error>");
}

TEST(ParamLoad, RejectsIntegerBeyondIntRange) {
    // `big` declares no range, but a value that does not fit an int must not wrap silently.
    std::string msg = paramLoadError({{"big", 4294967297ll}});
    EXPECT_NE(msg.find(std::string(kPrefix) + "big: "), std::string::npos) << msg;
    msg = paramLoadError({{"big", -3000000000ll}});
    EXPECT_NE(msg.find(std::string(kPrefix) + "big: "), std::string::npos) << msg;
}

TEST(ParamLoad, RejectsFloatBeyondFloatRange) {
    // `free` declares no range; 1e300 is a finite double but would become +inf as a float.
    std::string msg = paramLoadError({{"free", 1e300}});
    EXPECT_NE(msg.find(std::string(kPrefix) + "free: "), std::string::npos) << msg;
}

TEST(ParamLoad, RejectsBadChoice) {
    EXPECT_EQ(paramLoadError({{"mode", "exat"}}),
              std::string(kPrefix) +
                  "mode: 'exat' is not one of: fast, exact, off (did you mean 'exact'?)");
    EXPECT_EQ(
        paramLoadError({{"mode", "completely-different"}}),
        std::string(kPrefix) + "mode: 'completely-different' is not one of: fast, exact, off");
    // Choices are case-sensitive.
    EXPECT_NE(paramLoadError({{"mode", "FAST"}}), "<no error>");
}

TEST(ParamLoad, RejectsNonFinite) {
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::string p = kPrefix;
    EXPECT_EQ(paramLoadError({{"gain", inf}}), p + "gain: expected a finite number");
    // NaN compares false with every bound, so only the finiteness check catches it.
    EXPECT_EQ(paramLoadError({{"free", nan}}), p + "free: expected a finite number");
    EXPECT_EQ(paramLoadError({{"free", -inf}}), p + "free: expected a finite number");
    EXPECT_EQ(paramLoadError({{"tint", {0, nan, 0}}}), p + "tint: expected finite numbers");
}

TEST(ParamLoad, FailedLoadNamesTheFirstBadParameter) {
    // Parameters are checked in declaration order.
    std::string msg = paramLoadError({{"tint", "x"}, {"count", "x"}});
    EXPECT_NE(msg.find("/params/count:"), std::string::npos) << msg;
}

TEST(ParamSave, AllAndOnlyChanged) {
    auto pass = makePass();
    json all = saveParams(*pass, false);
    EXPECT_EQ(all, json({{"enabled", true},
                         {"count", 3},
                         {"big", 0},
                         {"gain", 0.5},
                         {"free", 2.0},
                         {"mode", "fast"},
                         {"label", "none"},
                         {"tint", {1.0, 0.5, 0.25}}}));
    EXPECT_EQ(saveParams(*pass, true), json::object());

    loadParams(*pass, {{"count", 7}, {"mode", "off"}, {"tint", {1, 1, 1}}, {"gain", 0.5}}, "g.json",
               "/p");
    // gain was set, but to its default: omitted.
    EXPECT_EQ(saveParams(*pass, true), json({{"count", 7}, {"mode", "off"}, {"tint", {1, 1, 1}}}));
}

TEST(ParamSave, RoundTrip) {
    auto a = makePass();
    loadParams(*a, {{"enabled", false}, {"big", -5}, {"label", "x y"}, {"tint", {0.5, 2, 3}}},
               "g.json", "/p");
    auto b = makePass();
    loadParams(*b, saveParams(*a, true), "saved.json", "/p");
    EXPECT_EQ(saveParams(*b, false), saveParams(*a, false));
    EXPECT_EQ(b->tint, glm::vec3(0.5f, 2.0f, 3.0f));
}

TEST(ParamDescribe, ListsEveryParameter) {
    auto pass = makePass();
    json d = describeParams(*pass);
    ASSERT_TRUE(d.is_array());
    ASSERT_EQ(d.size(), 8u);
    std::vector<std::string> names;
    for (const auto& p : d) names.push_back(p["name"]);
    EXPECT_EQ(names, (std::vector<std::string>{"enabled", "count", "big", "gain", "free", "mode",
                                               "label", "tint"}));

    EXPECT_EQ(
        d[0],
        json({{"name", "enabled"}, {"type", "bool"}, {"default", true}, {"doc", "a boolean"}}));
    EXPECT_EQ(d[1], json({{"name", "count"},
                          {"type", "int"},
                          {"default", 3},
                          {"min", 0.0},
                          {"max", 100.0},
                          {"doc", "an integer in 0..100"}}));
    // No declared range: no min/max.
    EXPECT_FALSE(d[2].contains("min"));
    EXPECT_FALSE(d[2].contains("max"));
    EXPECT_EQ(d[3]["type"], "float");
    EXPECT_EQ(d[3]["default"], 0.5);
    EXPECT_EQ(d[3]["min"], -1.0);
    EXPECT_EQ(d[3]["max"], 1.0);
    EXPECT_EQ(d[5]["type"], "string");
    EXPECT_EQ(d[5]["default"], "fast");
    EXPECT_EQ(d[5]["choices"], json({"fast", "exact", "off"}));
    EXPECT_EQ(d[5]["doc"], "a string with choices");
    EXPECT_FALSE(d[6].contains("choices"));
    EXPECT_EQ(d[7]["type"], "vec3");
    EXPECT_EQ(d[7]["default"], json({1.0, 0.5, 0.25}));
    EXPECT_EQ(d[7]["max"], 4.0);
}

TEST(ParamText, ConvertsByDeclaredType) {
    auto pass = makePass();
    const std::string flag = "--set p.x=...";
    json count = parseParamText(*pass, "count", "2", flag);
    EXPECT_TRUE(count.is_number_integer());
    EXPECT_EQ(count, 2);
    json gain = parseParamText(*pass, "gain", "0.25", flag);
    EXPECT_TRUE(gain.is_number());
    EXPECT_EQ(gain, 0.25);
    EXPECT_EQ(parseParamText(*pass, "enabled", "false", flag), false);
    json tint = parseParamText(*pass, "tint", "[1,2,3]", flag);
    EXPECT_EQ(tint, json({1, 2, 3}));
    // String parameters take the text as it is, even when it looks like JSON.
    EXPECT_EQ(parseParamText(*pass, "label", "noise", flag), "noise");
    EXPECT_EQ(parseParamText(*pass, "label", "2", flag), "2");
    EXPECT_TRUE(parseParamText(*pass, "label", "2", flag).is_string());
    EXPECT_EQ(parseParamText(*pass, "mode", "exact", flag), "exact");

    // And the converted values load.
    loadParams(*pass, {{"tint", tint}, {"count", count}, {"label", "noise"}}, flag, "");
    EXPECT_EQ(pass->tint, glm::vec3(1, 2, 3));
    EXPECT_EQ(pass->count, 2);
}

TEST(ParamText, RejectsUnknownParameterNamingTheFlag) {
    auto pass = makePass();
    try {
        parseParamText(*pass, "cuont", "1", "--set p.cuont=1");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(),
                     "--set p.cuont=1: pass 'p' (AllParams) has no parameter 'cuont' (did you "
                     "mean 'count'?)");
        EXPECT_EQ(e.file(), "--set p.cuont=1");
    }
}

TEST(ParamText, RejectsUnparsableText) {
    auto pass = makePass();
    try {
        parseParamText(*pass, "count", "two", "--set p.count=two");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_STREQ(e.what(), "--set p.count=two: cannot parse 'two' as a int value");
    }
    // Parsable but of the wrong type: converted as JSON, rejected by loadParams.
    json v = parseParamText(*pass, "count", "\"3\"", "--set p.count=\"3\"");
    EXPECT_THROW(loadParams(*pass, {{"count", v}}, "--set p.count=\"3\"", ""), InputError);
}

namespace {

// Records the parameters whose member holds something other than a value-initialized one.
class NonZeroParams : public ParamVisitor {
public:
    std::vector<std::string> names;
    void visit(const ParamSpec& s, bool& v, bool) override { note(s, v != bool{}); }
    void visit(const ParamSpec& s, int& v, int) override { note(s, v != int{}); }
    void visit(const ParamSpec& s, float& v, float) override { note(s, v != float{}); }
    void visit(const ParamSpec& s, std::string& v, const std::string&) override {
        note(s, !v.empty());
    }
    void visit(const ParamSpec& s, glm::vec3& v, const glm::vec3&) override {
        note(s, v != glm::vec3(0.0f));
    }

private:
    void note(const ParamSpec& s, bool nonZero) {
        if (nonZero) names.push_back(s.name);
    }
};

}  // namespace

// Issue 30, "one default per parameter": a built-in pass's default is written once, in its
// params() declaration (PassRegistry::create applies it). The members are value-initialized
// placeholders, so a constructor that sets a parameter (a second, possibly different default)
// fails here with the type and parameter.
TEST(ParamDefaults, BuiltinPassesWriteEachDefaultOnlyInParams) {
    registerBuiltinPasses();
    size_t checked = 0;
    for (const std::string& type : passRegistry().types()) {
        if (!passRegistry().origin(type).empty()) continue;               // a plugin's own business
        std::unique_ptr<Pass> raw = passRegistry().find(type)->create();  // no defaults applied
        NonZeroParams visitor;
        raw->params(visitor);
        for (const auto& name : visitor.names)
            ADD_FAILURE() << type << "::" << name
                          << " is set before its declared default is applied (initialize the "
                             "member with {} and keep the default in params())";
        ++checked;
    }
    EXPECT_GE(checked, 20u);
}
