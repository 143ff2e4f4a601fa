#include "core/util/JsonUtil.h"

#include <algorithm>
#include <set>

#include "core/util/DidYouMean.h"
#include "core/util/Error.h"

namespace fovea {

TextPosition textPosition(std::string_view text, size_t offset) {
    offset = std::min(offset, text.size());
    TextPosition position;
    size_t lineStart = 0;
    for (size_t i = 0; i < offset; ++i) {
        if (text[i] == '\n') {
            ++position.line;
            lineStart = i + 1;
        }
    }
    position.column = offset - lineStart + 1;
    return position;
}

std::string jsonPointerEscape(std::string_view token) {
    std::string escaped;
    escaped.reserve(token.size());
    for (char c : token) {
        if (c == '~') {
            escaped += "~0";
        } else if (c == '/') {
            escaped += "~1";
        } else {
            escaped += c;
        }
    }
    return escaped;
}

std::string jsonPointerAppend(const std::string& base, std::string_view key) {
    return base + "/" + jsonPointerEscape(key);
}

std::string jsonPointerAppend(const std::string& base, size_t index) {
    return base + "/" + std::to_string(index);
}

std::string truncateForMessage(std::string_view text, size_t maxChars) {
    if (text.size() <= maxChars) return std::string(text);
    size_t cut = maxChars;
    while (cut > 0 && (uint8_t(text[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 sequence
    return std::string(text.substr(0, cut)) + "\u2026";
}

std::string shortenQuotedSpans(std::string_view message, size_t maxChars) {
    std::string out;
    size_t i = 0;
    while (i < message.size()) {
        const size_t open = message.find('\'', i);
        if (open == std::string_view::npos) break;
        const size_t close = message.find('\'', open + 1);
        if (close == std::string_view::npos) break;
        out.append(message.substr(i, open + 1 - i));
        out += truncateForMessage(message.substr(open + 1, close - open - 1), maxChars);
        out += '\'';
        i = close + 1;
    }
    if (i < message.size()) out.append(message.substr(i));
    return truncateForMessage(out, 16 * maxChars);
}

std::string jsonTypeName(const nlohmann::json& value) {
    switch (value.type()) {
        case nlohmann::json::value_t::null:
            return "null";
        case nlohmann::json::value_t::boolean:
            return "boolean";
        case nlohmann::json::value_t::number_integer:
        case nlohmann::json::value_t::number_unsigned:
        case nlohmann::json::value_t::number_float:
            return "number";
        case nlohmann::json::value_t::string:
            return "string";
        case nlohmann::json::value_t::array:
            return "array";
        case nlohmann::json::value_t::object:
            return "object";
        default:
            return "binary";
    }
}

namespace {

// nlohmann's what() is "[json.exception.parse_error.101] parse error at line 3, column 15: syntax
// error while parsing value - unexpected ','; expected ']'". Its position is recomputed by us
// (from parse_error::byte, so it is exact for the text we hold); the rest is reworded to
// "JSON syntax error in value: unexpected ','; expected ']'".
std::string describeParseError(const std::string& what) {
    std::string message = what;
    if (size_t bracket = message.find("] ");
        message.rfind("[json.exception.", 0) == 0 && bracket != std::string::npos) {
        message.erase(0, bracket + 2);
    }
    if (message.rfind("parse error", 0) == 0) {
        size_t colon = message.find(": ");
        message = colon == std::string::npos ? std::string() : message.substr(colon + 2);
    }
    const std::string syntaxPrefix = "syntax error ";
    if (message.rfind(syntaxPrefix, 0) != 0) return message;
    std::string rest = message.substr(syntaxPrefix.size());
    std::string context;
    if (rest.rfind("while parsing ", 0) == 0) {
        size_t dash = rest.find(" - ");
        if (dash == std::string::npos) return message;
        context = rest.substr(14, dash - 14);
        rest = rest.substr(dash + 3);
    } else if (rest.rfind("- ", 0) == 0) {
        rest = rest.substr(2);
    }
    return "JSON syntax error" + (context.empty() ? std::string() : " in " + context) + ": " + rest;
}

// Tracks where the parser is, so a duplicate key can be reported with the pointer of its object.
// It also bounds the nesting depth: nlohmann parses iteratively, but copying or walking a value
// nested 70,000 levels deep (graph params, glTF extras seen by tinygltf) recurses and overflows
// the stack, so such a file is refused while it is parsed.
class DuplicateKeyDetector {
public:
    explicit DuplicateKeyDetector(const std::string& file) : mFile(file) {}

    bool onEvent(nlohmann::json::parse_event_t event, const nlohmann::json& parsed) {
        using Event = nlohmann::json::parse_event_t;
        switch (event) {
            case Event::object_start:
            case Event::array_start:
                if (mStack.size() >= kMaxJsonDepth)
                    throw InputError(mFile, currentPointer(),
                                     "JSON nested deeper than " + std::to_string(kMaxJsonDepth) +
                                         " levels (refused: deeper values would exhaust the "
                                         "stack)");
                beginElement();
                mStack.emplace_back(event == Event::object_start);
                break;
            case Event::object_end:
            case Event::array_end:
                if (!mStack.empty()) mStack.pop_back();
                break;
            case Event::key: {
                Frame& frame = mStack.back();
                frame.key = parsed.get<std::string>();
                if (!frame.keys.insert(frame.key).second && !mDuplicateFound) {
                    mDuplicateFound = true;
                    mDuplicateKey = frame.key;
                    mDuplicatePointer = pointerBelowTop();
                }
                break;
            }
            case Event::value:
                beginElement();
                break;
        }
        return true;
    }

    bool found() const { return mDuplicateFound; }
    const std::string& key() const { return mDuplicateKey; }
    const std::string& pointer() const { return mDuplicatePointer; }

private:
    struct Frame {
        explicit Frame(bool object) : isObject(object) {}
        bool isObject;
        std::set<std::string> keys;  // objects: keys seen so far
        std::string key;             // objects: key of the member being parsed
        size_t count = 0;            // arrays: elements started so far
    };

    // Array elements carry no key event, so count them as they start.
    void beginElement() {
        if (!mStack.empty() && !mStack.back().isObject) ++mStack.back().count;
    }

public:
    // Pointer of the value being parsed now (the member after the last key, or the next element
    // of the innermost array); "" at the root. Truncated: a key may be megabytes long.
    std::string currentPointer() const {
        std::string pointer;
        for (size_t i = 0; i < mStack.size() && pointer.size() <= kMaxPointerChars; ++i) {
            const Frame& frame = mStack[i];
            const bool top = i + 1 == mStack.size();
            pointer = frame.isObject
                          ? jsonPointerAppend(pointer, frame.key)
                          : jsonPointerAppend(pointer, top ? frame.count : frame.count - 1);
        }
        return truncateForMessage(pointer, kMaxPointerChars);
    }

private:
    static constexpr size_t kMaxPointerChars = 200;

    // Pointer of the innermost (top) container.
    std::string pointerBelowTop() const {
        std::string pointer;
        for (size_t i = 0; i + 1 < mStack.size(); ++i) {
            const Frame& frame = mStack[i];
            pointer = frame.isObject ? jsonPointerAppend(pointer, frame.key)
                                     : jsonPointerAppend(pointer, frame.count - 1);
        }
        return pointer;
    }

    std::string mFile;
    std::vector<Frame> mStack;
    bool mDuplicateFound = false;
    std::string mDuplicateKey;
    std::string mDuplicatePointer;
};

}  // namespace

nlohmann::json parseJsonText(std::string_view text, const std::string& file) {
    // nlohmann's lexer reads a NUL byte as the end of the input, so "{...}\0garbage" parsed as
    // the object alone (issue 33, class 6). JSON text never holds a raw NUL (RFC 8259 §7: control
    // characters in strings are escaped), so one is an error at its position.
    if (const size_t nul = text.find('\0'); nul != std::string_view::npos) {
        const TextPosition at = textPosition(text, nul);
        throw InputError(file, "",
                         "line " + std::to_string(at.line) + ", column " +
                             std::to_string(at.column) +
                             ": a NUL byte (JSON text cannot contain one; is this a binary file?)");
    }
    DuplicateKeyDetector detector(file);
    nlohmann::json root;
    try {
        root = nlohmann::json::parse(
            text.begin(), text.end(),
            [&detector](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
                return detector.onEvent(event, parsed);
            });
    } catch (const nlohmann::json::parse_error& e) {
        // parse_error::byte is the 1-based index of the last character read (the culprit).
        TextPosition at = textPosition(text, e.byte > 0 ? e.byte - 1 : 0);
        throw InputError(file, "",
                         "line " + std::to_string(at.line) + ", column " +
                             std::to_string(at.column) + ": " + describeParseError(e.what()));
    } catch (const nlohmann::json::out_of_range& e) {
        // 406: a number beyond double ("1e400"); the parser stopped at the value being read.
        std::string what = e.what();
        if (size_t bracket = what.find("] "); bracket != std::string::npos)
            what.erase(0, bracket + 2);
        throw InputError(file, detector.currentPointer(),
                         truncateForMessage(what, 200) + " (the number does not fit a double)");
    }
    if (detector.found()) {
        throw InputError(file, detector.pointer(), "duplicate key '" + detector.key() + "'");
    }
    return root;
}

// --- JsonNode -----------------------------------------------------------------------------------

JsonNode::JsonNode(const nlohmann::json& value, std::string file, std::string pointer)
    : mValue(&value), mFile(std::move(file)), mPointer(std::move(pointer)) {}

void JsonNode::fail(const std::string& message) const {
    throw InputError(mFile, mPointer, message);
}

std::optional<JsonNode> JsonNode::find(std::string_view key) const {
    expectObject();
    auto it = mValue->find(std::string(key));
    if (it == mValue->end()) return std::nullopt;
    return JsonNode(*it, mFile, jsonPointerAppend(mPointer, key));
}

JsonNode JsonNode::require(std::string_view key) const {
    std::optional<JsonNode> member = find(key);
    if (!member) fail("missing required field '" + std::string(key) + "'");
    return *member;
}

void JsonNode::checkFields(const std::vector<std::string>& allowed) const {
    expectObject();
    for (const auto& [key, value] : mValue->items()) {
        if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
            fail("unknown field '" + key + "'" + didYouMean(key, allowed));
        }
    }
}

size_t JsonNode::size() const {
    expectArray();
    return mValue->size();
}

JsonNode JsonNode::at(size_t index) const {
    if (index >= size()) {
        fail("index " + std::to_string(index) + " out of range (" + std::to_string(size()) +
             " elements)");
    }
    return JsonNode((*mValue)[index], mFile, jsonPointerAppend(mPointer, index));
}

std::vector<JsonNode> JsonNode::elements() const {
    std::vector<JsonNode> result;
    result.reserve(size());
    for (size_t i = 0; i < mValue->size(); ++i) result.push_back(at(i));
    return result;
}

const JsonNode& JsonNode::expectObject() const {
    if (!mValue->is_object()) fail("expected an object, got " + jsonTypeName(*mValue));
    return *this;
}

const JsonNode& JsonNode::expectArray() const {
    if (!mValue->is_array()) fail("expected an array, got " + jsonTypeName(*mValue));
    return *this;
}

std::string JsonNode::asString() const {
    if (!mValue->is_string()) fail("expected a string, got " + jsonTypeName(*mValue));
    return mValue->get<std::string>();
}

bool JsonNode::asBool() const {
    if (!mValue->is_boolean()) fail("expected a boolean, got " + jsonTypeName(*mValue));
    return mValue->get<bool>();
}

double JsonNode::asNumber() const {
    if (!mValue->is_number()) fail("expected a number, got " + jsonTypeName(*mValue));
    return mValue->get<double>();
}

int64_t JsonNode::asInt(int64_t min, int64_t max) const {
    // Show the offending value for non-integral numbers: "got number" would read as a
    // contradiction.
    if (mValue->is_number_float()) fail("expected an integer, got " + mValue->dump());
    if (!mValue->is_number_integer()) fail("expected an integer, got " + jsonTypeName(*mValue));
    std::string range = "(allowed " + std::to_string(min) + ".." + std::to_string(max) + ")";
    if (mValue->is_number_unsigned() &&
        mValue->get<uint64_t>() > static_cast<uint64_t>(std::numeric_limits<int64_t>::max())) {
        fail("out of range: " + mValue->dump() + " " + range);
    }
    int64_t value = mValue->get<int64_t>();
    if (value < min || value > max) fail("out of range: " + std::to_string(value) + " " + range);
    return value;
}

uint64_t JsonNode::asUnsigned() const {
    const char* expected = "expected a non-negative integer, got ";
    if (mValue->is_number_float() ||
        (mValue->is_number_integer() && !mValue->is_number_unsigned() &&
         mValue->get<int64_t>() < 0)) {
        fail(expected + mValue->dump());
    }
    if (!mValue->is_number_integer()) fail(expected + jsonTypeName(*mValue));
    return mValue->get<uint64_t>();
}

}  // namespace fovea
