// JSON helpers for reading user-written files (graphs, pass parameters). Every error they raise is
// an InputError naming the file and the JSON pointer of the offending value, so a user can find
// the mistake without guessing: "graphs/x.json: /passes/3/params/spp: expected an integer, got
// string".
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fovea {

// 1-based line and column (in bytes) of a position in a text.
struct TextPosition {
    size_t line = 1;
    size_t column = 1;
};

// Position of the byte at `offset` (0-based). An offset at or past the end points just after the
// last character, which is where "unexpected end of input" errors belong.
TextPosition textPosition(std::string_view text, size_t offset);

// RFC 6901 escaping of one reference token: '~' -> "~0", '/' -> "~1".
std::string jsonPointerEscape(std::string_view token);

// "/passes" + "params" -> "/passes/params"; the key is escaped.
std::string jsonPointerAppend(const std::string& base, std::string_view key);
// "/passes" + 3 -> "/passes/3".
std::string jsonPointerAppend(const std::string& base, size_t index);

// "null", "boolean", "number", "string", "array", "object" — the words used in type errors.
std::string jsonTypeName(const nlohmann::json& value);

// Deepest nesting of objects/arrays parseJsonText accepts (graphs and glTF files need < 20).
constexpr size_t kMaxJsonDepth = 256;

// `text` cut to at most `maxChars` bytes (on a UTF-8 boundary) followed by "…" when longer: for
// echoing user text in error messages (a 10 MB pass type must not make a 10 MB line).
std::string truncateForMessage(std::string_view text, size_t maxChars = 200);

// Every '...'-quoted span of `message` longer than `maxChars` cut with truncateForMessage (the
// closing quote kept), then the whole message cut at 16 * maxChars: error lines echo user text.
std::string shortenQuotedSpans(std::string_view message, size_t maxChars = 200);

// Parses `text`, turning syntax errors into InputError(file, "", "line L, column C: ...") and
// rejecting nesting deeper than kMaxJsonDepth and numbers beyond double ("1e400") as
// InputError(file, <pointer>, ...), and rejecting duplicate object keys (nlohmann would silently
// keep the last one, hiding a typo'd copy-paste) as InputError(file, <pointer of the object>,
// "duplicate key 'k'").
nlohmann::json parseJsonText(std::string_view text, const std::string& file);

// A JSON value together with where it came from. Accessors check the type and throw InputError
// naming file and pointer; the node only borrows the value, so the root must outlive it.
class JsonNode {
public:
    JsonNode(const nlohmann::json& value, std::string file, std::string pointer = "");

    const nlohmann::json& value() const { return *mValue; }
    const std::string& file() const { return mFile; }
    const std::string& pointer() const { return mPointer; }

    // Throws InputError(file, pointer, message).
    [[noreturn]] void fail(const std::string& message) const;

    // --- objects (each of these first checks that the node is an object) ---
    std::optional<JsonNode> find(std::string_view key) const;
    // A missing field is reported at this object's pointer: "missing required field 'name'".
    JsonNode require(std::string_view key) const;
    // "unknown field 'parms' (did you mean 'params'?)", reported at this object's pointer.
    void checkFields(const std::vector<std::string>& allowed) const;

    // --- arrays ---
    size_t size() const;  // element count; checks that the node is an array
    JsonNode at(size_t index) const;
    std::vector<JsonNode> elements() const;

    // --- type checks; "expected a string, got number" ---
    const JsonNode& expectObject() const;
    const JsonNode& expectArray() const;
    std::string asString() const;
    bool asBool() const;
    double asNumber() const;
    // Integers only (1.0 is rejected: the files are hand-written and 1.5 is almost surely a slip).
    // Outside [min, max]: "out of range: 9 (allowed 0..8)".
    int64_t asInt(int64_t min = std::numeric_limits<int64_t>::min(),
                  int64_t max = std::numeric_limits<int64_t>::max()) const;
    // The whole uint64 range, for seeds and hashes: "expected a non-negative integer, got -1".
    uint64_t asUnsigned() const;

private:
    const nlohmann::json* mValue;
    std::string mFile;
    std::string mPointer;
};

}  // namespace fovea
