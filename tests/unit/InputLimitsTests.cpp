// Limits on user input that used to crash or pass silently (issue 16): JSON nesting depth and
// numbers beyond double in parseJsonText (graphs, camera paths and glTF share it), and the
// truncation of user text echoed in error messages. CPU only.
#include <gtest/gtest.h>

#include <string>

#include "core/util/Error.h"
#include "core/util/JsonUtil.h"

using namespace fovea;

namespace {

std::string nestedArrays(size_t depth) {
    return std::string(depth, '[') + "1" + std::string(depth, ']');
}

InputError parseError(const std::string& text) {
    try {
        parseJsonText(text, "f.json");
    } catch (const InputError& e) {
        return e;
    }
    ADD_FAILURE() << "parsed: " << text.substr(0, 80);
    return InputError("", "", "");
}

}  // namespace

TEST(JsonUtilLimits, NestingDepthIsBounded) {
    EXPECT_NO_THROW(parseJsonText(nestedArrays(kMaxJsonDepth), "f.json"));
    InputError e = parseError(nestedArrays(kMaxJsonDepth + 1));
    EXPECT_EQ(e.file(), "f.json");
    EXPECT_NE(std::string(e.what()).find("nested deeper than 256"), std::string::npos) << e.what();
    // 100,000 levels: refused at level 257, no stack overflow, a pointer of bounded length.
    InputError deep = parseError(R"({"a": )" + nestedArrays(100000) + "}");
    EXPECT_EQ(deep.pointer().rfind("/a/0/0", 0), 0u) << deep.pointer();
    EXPECT_LE(deep.pointer().size(), 210u);
}

TEST(JsonUtilLimits, NumberBeyondDoubleNamesThePointer) {
    InputError e = parseError(R"({"a": [1, {"b": 1e400}]})");
    EXPECT_EQ(e.file(), "f.json");
    EXPECT_EQ(e.pointer(), "/a/1/b");
    EXPECT_NE(std::string(e.what()).find("1e400"), std::string::npos) << e.what();
    EXPECT_EQ(parseError(R"([0, -1e999])").pointer(), "/1");
    EXPECT_EQ(parseError("1e400").pointer(), "");
    EXPECT_NO_THROW(parseJsonText("[1e308, 1e-400]", "f.json"));  // underflow is 0, not an error
}

TEST(JsonUtilLimits, MessagesCutLongQuotedValues) {
    const std::string longValue(5000, 'x');
    const std::string message = "pass 'src' has type '" + longValue + "' (see 'fovea passes')";
    const std::string cut = shortenQuotedSpans(message);
    EXPECT_LT(cut.size(), 300u);
    EXPECT_NE(cut.find("'" + std::string(200, 'x') + "\u2026'"), std::string::npos) << cut;
    EXPECT_NE(cut.find("'src'"), std::string::npos);
    EXPECT_NE(cut.find("'fovea passes')"), std::string::npos);
    EXPECT_EQ(shortenQuotedSpans("no quotes here"), "no quotes here");
    EXPECT_EQ(shortenQuotedSpans("unbalanced 'quote"), "unbalanced 'quote");
    // Never cut inside a UTF-8 sequence.
    std::string accents;
    for (int i = 0; i < 300; ++i) accents += "\u00e9";
    const std::string cutAccents = truncateForMessage(accents, 201);
    EXPECT_EQ(cutAccents, accents.substr(0, 200) + "\u2026");
}

TEST(JsonUtilLimits, NulByteIsAnErrorNotTheEndOfTheText) {
    // nlohmann's lexer stops at a NUL: "{...}\0garbage" used to parse as the object (issue 33).
    // Built with push_back: gcc 12 reports a false -Warray-bounds on std::string + '\0' + "...".
    std::string text = "{\"a\": 1}\n";
    text.push_back('\0');
    text += "garbage";
    InputError e = parseError(text);
    EXPECT_EQ(e.file(), "f.json");
    EXPECT_NE(std::string(e.what()).find("line 2, column 1: a NUL byte"), std::string::npos)
        << e.what();
    std::string inString = "[\"x";
    inString.push_back('\0');
    inString += "\"]";
    EXPECT_NE(std::string(parseError(inString).what()).find("NUL"), std::string::npos);
}
