// Non-throwing typed access to the raw glTF JSON, for the checks that run before tinygltf sees the
// file. tinygltf reads an optional property of the wrong type as its default ("mesh": "0" becomes
// "no mesh"), which would be a silent default; these getters record every such value as an Issue
// with its JSON pointer and read it as absent, so one bad value never hides the next one.
// Whether an Issue is an error or a warning is decided later, once the traversal (GltfUsage) knows
// whether the scene uses the entity it belongs to.
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fovea::scene::gltf {

using Json = nlohmann::json;

struct Issue {
    std::string pointer;  // RFC 6901 pointer into the glTF JSON ("" = the file as a whole)
    std::string message;
};

class Issues {
public:
    void add(std::string pointer, std::string message) {
        mList.push_back({std::move(pointer), std::move(message)});
    }
    const std::vector<Issue>& list() const { return mList; }

private:
    std::vector<Issue> mList;
};

// glTF JSON integers may be written as 3.0 (the validator accepts it), and 2^53 is the largest
// integer a JSON number holds exactly; anything above is not a valid index, count or offset.
constexpr uint64_t kMaxJsonInteger = uint64_t(1) << 53;

// One JSON value with its pointer. A view: the root JSON must outlive it. An invalid view (absent
// property, or one of the wrong type, already recorded) answers every getter with "absent".
class JsonView {
public:
    JsonView() = default;
    JsonView(const Json* value, std::string pointer, Issues* issues)
        : mValue(value), mPointer(std::move(pointer)), mIssues(issues) {}

    // The same view without issue recording, for code that re-reads what the checks report.
    JsonView silent() const { return JsonView(mValue, mPointer, nullptr); }

    bool exists() const { return mValue != nullptr; }
    bool isObject() const { return mValue && mValue->is_object(); }
    const Json* raw() const { return mValue; }
    const std::string& pointer() const { return mPointer; }
    std::string pointerTo(std::string_view key) const;
    std::string pointerTo(size_t index) const;

    // --- members of an object (absent if this view is not an object) ---
    bool has(std::string_view key) const;
    const Json* member(std::string_view key) const;
    // Records "missing required property 'key'" at this object's pointer; true if present.
    bool require(std::string_view key) const;
    std::optional<uint64_t> uint(std::string_view key) const;  // non-negative integer <= 2^53
    std::optional<double> number(std::string_view key) const;  // any JSON number (may be inf)
    std::optional<std::string> string(std::string_view key) const;
    std::optional<bool> boolean(std::string_view key) const;
    // Exactly `count` numbers; a wrong length is recorded.
    std::optional<std::vector<double>> numbers(std::string_view key, size_t count) const;
    JsonView object(std::string_view key) const;  // invalid if absent or not an object
    JsonView array(std::string_view key) const;   // invalid if absent or not an array

    // --- elements of an array ---
    size_t size() const { return mValue && mValue->is_array() ? mValue->size() : 0; }
    JsonView element(size_t index) const;
    std::optional<uint64_t> uintAt(size_t index) const;
    std::optional<std::string> stringAt(size_t index) const;

    void issue(const std::string& message) const;
    void issueAt(std::string_view key, const std::string& message) const;

private:
    const Json* mValue = nullptr;
    std::string mPointer;
    Issues* mIssues = nullptr;
};

// The glTF document's top-level collections ("accessors", "nodes", ...). A collection that is not
// an array is recorded once and then reads as empty; an element that is not an object reads as an
// invalid view (also recorded once, by checkCollections).
class GltfJson {
public:
    GltfJson(const Json& root, Issues& issues) : mRoot(&root), mIssues(&issues) {}

    const Json& root() const { return *mRoot; }
    Issues& issues() const { return *mIssues; }
    JsonView rootView() const { return JsonView(mRoot, "", mIssues); }

    size_t count(std::string_view collection) const;
    JsonView entity(std::string_view collection, size_t index) const;
    // The KHR_lights_punctual lights live under /extensions/KHR_lights_punctual/lights.
    size_t lightCount() const;
    JsonView light(size_t index) const;

    // Records non-array collections and non-object elements.
    void checkCollections() const;

private:
    const Json* collection(std::string_view name) const;
    const Json* lightArray() const;

    const Json* mRoot;
    Issues* mIssues;
};

// Collections of the glTF root, in document order.
const std::vector<std::string>& gltfCollections();

// "%2F" -> "/" etc. (RFC 3986 percent-decoding of a relative URI); false on a malformed escape.
bool percentDecode(std::string_view uri, std::string& out);

}  // namespace fovea::scene::gltf
