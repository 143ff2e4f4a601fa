// Compile-time checks of the utility passes (Blit, Tonemap, Combine, ImageSource): integer
// formats their shaders cannot read or write are rejected at compile, naming pass and field or
// parameter; bypass pairs of different size or format are rejected by the compile stages (so
// `fovea validate` agrees with `fovea run`); parameter docs say what the code does. CPU only.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "core/graph/CompilerStages.h"
#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/image/ImageIO.h"
#include "core/util/Error.h"
#include "core/vk/Formats.h"
#include "passes/Blit/BlitPass.h"
#include "passes/Combine/CombinePass.h"
#include "passes/ImageSource/ImageSourcePass.h"
#include "passes/RegisterPasses.h"
#include "passes/Tonemap/TonemapPass.h"

namespace fs = std::filesystem;
using namespace fovea;
using namespace fovea::graph;

namespace {

// --- integer formats ------------------------------------------------------------------------

// A source of an integer image (what a G-buffer's ids look like). Never executed.
class UintSource : public Pass {
public:
    void reflect(Reflection& r) const override { r.output("ids", vk::Format::eR32Uint).screen(); }
    void execute(ExecuteContext&) override {}
};

template <class T>
PassTypeInfo typeInfo(const char* type) {
    return {type, "test", [] { return std::make_unique<T>(); }};
}

const PassRegistry& integerRegistry() {
    static PassRegistry registry = [] {
        PassRegistry r;
        r.add(typeInfo<UintSource>("UintSource"));
        r.add(typeInfo<passes::ImageSourcePass>("ImageSource"));
        r.add(typeInfo<passes::BlitPass>("Blit"));
        r.add(typeInfo<passes::TonemapPass>("Tonemap"));
        r.add(typeInfo<passes::CombinePass>("Combine"));
        return r;
    }();
    return registry;
}

CompileOptions options32() {
    CompileOptions o;
    o.width = 32;
    o.height = 32;
    return o;
}

// The InputError message compiling `text` gives, or "<no error>".
std::string compileError(const std::string& text, const PassRegistry& registry) {
    try {
        compileGraphPlan(parseGraphText(text, "g.json"), registry, options32());
    } catch (const InputError& e) {
        return e.what();
    }
    return "<no error>";
}

// ids -> <type>.<field> (plus a float source on the other Combine input).
std::string integerInto(const std::string& type, const std::string& field,
                        const std::string& output) {
    std::string edges = R"({ "from": "ids.ids", "to": "p.)" + field + R"(" })";
    if (type == "Combine")
        edges += std::string(R"(, { "from": "f.color", "to": "p.)") + (field == "a" ? "b" : "a") +
                 R"(" })";
    return R"({ "version": 1,
      "passes": [ { "name": "ids", "type": "UintSource" }, { "name": "f", "type": "ImageSource" },
                  { "name": "p", "type": ")" +
           type + R"(" } ],
      "edges": [ )" +
           edges + R"( ], "outputs": [ "p.)" + output + R"(" ] })";
}

void expectIntegerRejected(const std::string& type, const std::string& field,
                           const std::string& output) {
    SCOPED_TRACE(type + "." + field);
    std::string error = compileError(integerInto(type, field, output), integerRegistry());
    EXPECT_EQ(error.rfind("g.json: /edges/0: ", 0), 0u) << error;
    EXPECT_NE(error.find("pass 'p' (" + type + ")"), std::string::npos) << error;
    EXPECT_NE(error.find("input '" + field + "'"), std::string::npos) << error;
    EXPECT_NE(error.find("r32ui"), std::string::npos) << error;
}

TEST(UtilityPassFormats, TonemapRejectsAnIntegerInput) {
    expectIntegerRejected("Tonemap", "color", "ldr");
}

TEST(UtilityPassFormats, CombineRejectsIntegerInputs) {
    expectIntegerRejected("Combine", "a", "result");
    expectIntegerRejected("Combine", "b", "result");
}

TEST(UtilityPassFormats, BlitRejectsAnIntegerInput) {
    expectIntegerRejected("Blit", "color", "result");
}

TEST(UtilityPassFormats, BlitOffersNoIntegerOutputFormat) {
    for (const std::string format : {"r32ui", "rg32ui", "rgba32ui"}) {
        SCOPED_TRACE(format);
        std::string error = compileError(R"({ "version": 1,
          "passes": [ { "name": "f", "type": "ImageSource" },
                      { "name": "b", "type": "Blit", "params": { "format": ")" +
                                             format + R"(" } } ],
          "edges": [ { "from": "f.color", "to": "b.color" } ], "outputs": [ "b.result" ] })",
                                         integerRegistry());
        EXPECT_EQ(error.rfind("g.json: /passes/1/params/format: '" + format + "' is not one of", 0),
                  0u)
            << error;
    }
    // Every float/unorm format is still offered.
    passes::BlitPass blit;
    bool found = false;
    for (const auto& p : describeParams(blit)) {
        if (p["name"] != "format") continue;
        found = true;
        for (const auto& name : gpu::formatNames()) {
            bool offered =
                std::find(p["choices"].begin(), p["choices"].end(), name) != p["choices"].end();
            EXPECT_EQ(offered, !gpu::formatIsUint(gpu::parseFormat(name))) << name;
        }
    }
    EXPECT_TRUE(found);
}

TEST(UtilityPassFormats, FloatAndUnormInputsStillCompile) {
    // rgba8 (unorm) into Combine and Tonemap; rgba16f through Blit.
    EXPECT_EQ(compileError(R"({ "version": 1,
      "passes": [ { "name": "f", "type": "ImageSource" },
                  { "name": "b", "type": "Blit", "params": { "format": "rgba16f" } },
                  { "name": "t", "type": "Tonemap" }, { "name": "c", "type": "Combine" },
                  { "name": "t2", "type": "Tonemap" } ],
      "edges": [ { "from": "f.color", "to": "b.color" }, { "from": "b.result", "to": "t.color" },
                 { "from": "t.ldr", "to": "c.a" }, { "from": "c.result", "to": "t2.color" } ],
      "outputs": [ "t2.ldr" ] })",
                           integerRegistry()),
              "<no error>");
}

// --- bypass pairs at compile ------------------------------------------------------------------

const fs::path kBadCompile = fs::path(FOVEA_TEST_DIR) / "graph" / "bad" / "compile";

TEST(UtilityPassBypass, SizeOrFormatMismatchFailsInTheCompileStages) {
    registerBuiltinPasses();
    const fs::path file = kBadCompile / "bypass_size_mismatch.json";
    try {
        compileGraphPlan(parseGraphFile(file), passRegistry(), options32());
        ADD_FAILURE() << "compiled";
    } catch (const InputError& e) {
        EXPECT_EQ(std::string(e.what()),
                  file.string() +
                      ": /passes/1: pass 'b' bypasses 'color' into 'result' but they "
                      "differ in size or format");
    }
    auto blit = [](const std::string& params) {
        return R"({ "version": 1, "passes": [ { "name": "src", "type": "ImageSource" },
          { "name": "b", "type": "Blit", "params": )" +
               params + R"( } ],
          "edges": [ { "from": "src.color", "to": "b.color" } ], "outputs": [ "b.result" ] })";
    };
    EXPECT_EQ(compileError(blit(R"({ "activeEvery": 3, "format": "rgba16f" })"), passRegistry()),
              "g.json: /passes/1: pass 'b' bypasses 'color' into 'result' but they differ in "
              "size or format");
    // Equal size and format, or no bypass at all: fine.
    EXPECT_EQ(compileError(blit(R"({ "activeEvery": 3 })"), passRegistry()), "<no error>");
    EXPECT_EQ(compileError(blit(R"({ "scale": 0.5, "format": "rgba16f" })"), passRegistry()),
              "<no error>");
}

TEST(UtilityPassBypass, ACulledBypassPassIsNotChecked) {
    registerBuiltinPasses();
    // The mismatching Blit is disabled: it never runs, so it cannot fail a copy.
    EXPECT_EQ(compileError(R"({ "version": 1, "passes": [ { "name": "src", "type": "ImageSource" },
          { "name": "b", "type": "Blit", "enabled": false,
            "params": { "activeEvery": 2, "scale": 0.5 } } ],
          "edges": [ { "from": "src.color", "to": "b.color" } ],
          "outputs": [ "b.result", "src.color" ] })",
                           passRegistry()),
              "<no error>");
}

// --- documentation says what the code does ----------------------------------------------------

std::string paramDoc(Pass& pass, const std::string& name) {
    for (const auto& p : describeParams(pass))
        if (p["name"] == name) return p["doc"];
    return "";
}

TEST(UtilityPassDocs, ImageSourceSeedDocStatesTheFormula) {
    passes::ImageSourcePass source;
    const std::string seed = paramDoc(source, "seed");
    EXPECT_EQ(seed.find("added to"), std::string::npos) << seed;
    EXPECT_NE(seed.find("seed + 7919 * run seed"), std::string::npos) << seed;
    EXPECT_NE(seed.find("104729 * frame index"), std::string::npos) << seed;
    const std::string pattern = paramDoc(source, "pattern");
    EXPECT_NE(pattern.find("alpha is the frame number"), std::string::npos) << pattern;
}

TEST(UtilityPassDocs, CombineDocSaysAlphaIsCombined) {
    passes::CombinePass combine;
    EXPECT_NE(paramDoc(combine, "weightA").find("alpha included"), std::string::npos);
    EXPECT_NE(paramDoc(combine, "weightB").find("alpha included"), std::string::npos);
}

// docs/passes/<Type>.md: its tables are generated from the registry for every pass type and
// checked by CliPasses.DocPagesAreCurrentForEveryPassType.

}  // namespace
