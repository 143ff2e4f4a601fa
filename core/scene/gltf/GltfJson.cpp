#include "core/scene/gltf/GltfJson.h"

#include <cmath>

#include "core/util/JsonUtil.h"

namespace fovea::scene::gltf {

namespace {

// Reads a JSON number as a glTF integer: integral, non-negative, at most 2^53.
std::optional<uint64_t> asUint(const Json& value) {
    if (value.is_number_unsigned()) {
        uint64_t v = value.get<uint64_t>();
        if (v <= kMaxJsonInteger) return v;
        return std::nullopt;
    }
    if (value.is_number_integer()) return std::nullopt;  // signed: only negative values land here
    if (value.is_number_float()) {
        double d = value.get<double>();
        if (std::isfinite(d) && d >= 0.0 && d <= double(kMaxJsonInteger) && std::floor(d) == d) {
            return uint64_t(d);
        }
    }
    return std::nullopt;
}

std::string describe(const Json& value) {
    std::string text = value.dump(-1, ' ', false, Json::error_handler_t::replace);
    if (text.size() > 40) {
        text.resize(37);
        text += "...";
    }
    return text;
}

}  // namespace

std::string JsonView::pointerTo(std::string_view key) const {
    return jsonPointerAppend(mPointer, key);
}

std::string JsonView::pointerTo(size_t index) const {
    return jsonPointerAppend(mPointer, index);
}

void JsonView::issue(const std::string& message) const {
    if (mIssues) mIssues->add(mPointer, message);
}

void JsonView::issueAt(std::string_view key, const std::string& message) const {
    if (mIssues) mIssues->add(pointerTo(key), message);
}

const Json* JsonView::member(std::string_view key) const {
    if (!isObject()) return nullptr;
    auto it = mValue->find(key);
    return it == mValue->end() ? nullptr : &*it;
}

bool JsonView::has(std::string_view key) const {
    return member(key) != nullptr;
}

bool JsonView::require(std::string_view key) const {
    if (!isObject()) return false;
    if (has(key)) return true;
    issue("missing required property '" + std::string(key) + "'");
    return false;
}

std::optional<uint64_t> JsonView::uint(std::string_view key) const {
    const Json* value = member(key);
    if (!value) return std::nullopt;
    std::optional<uint64_t> v = asUint(*value);
    if (!v) issueAt(key, "expected a non-negative integer, got " + describe(*value));
    return v;
}

std::optional<double> JsonView::number(std::string_view key) const {
    const Json* value = member(key);
    if (!value) return std::nullopt;
    if (!value->is_number()) {
        issueAt(key, "expected a number, got " + jsonTypeName(*value));
        return std::nullopt;
    }
    return value->get<double>();
}

std::optional<std::string> JsonView::string(std::string_view key) const {
    const Json* value = member(key);
    if (!value) return std::nullopt;
    if (!value->is_string()) {
        issueAt(key, "expected a string, got " + jsonTypeName(*value));
        return std::nullopt;
    }
    return value->get<std::string>();
}

std::optional<bool> JsonView::boolean(std::string_view key) const {
    const Json* value = member(key);
    if (!value) return std::nullopt;
    if (!value->is_boolean()) {
        issueAt(key, "expected a boolean, got " + jsonTypeName(*value));
        return std::nullopt;
    }
    return value->get<bool>();
}

std::optional<std::vector<double>> JsonView::numbers(std::string_view key, size_t count) const {
    const Json* value = member(key);
    if (!value) return std::nullopt;
    if (!value->is_array()) {
        issueAt(key, "expected an array of " + std::to_string(count) + " numbers, got " +
                         jsonTypeName(*value));
        return std::nullopt;
    }
    if (value->size() != count) {
        issueAt(key, "expected " + std::to_string(count) + " numbers, got " +
                         std::to_string(value->size()));
        return std::nullopt;
    }
    std::vector<double> out;
    out.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        const Json& element = (*value)[i];
        if (!element.is_number()) {
            if (mIssues) {
                mIssues->add(jsonPointerAppend(pointerTo(key), i),
                             "expected a number, got " + jsonTypeName(element));
            }
            return std::nullopt;
        }
        out.push_back(element.get<double>());
    }
    return out;
}

JsonView JsonView::object(std::string_view key) const {
    const Json* value = member(key);
    if (!value) return {};
    if (!value->is_object()) {
        issueAt(key, "expected an object, got " + jsonTypeName(*value));
        return {};
    }
    return JsonView(value, pointerTo(key), mIssues);
}

JsonView JsonView::array(std::string_view key) const {
    const Json* value = member(key);
    if (!value) return {};
    if (!value->is_array()) {
        issueAt(key, "expected an array, got " + jsonTypeName(*value));
        return {};
    }
    return JsonView(value, pointerTo(key), mIssues);
}

JsonView JsonView::element(size_t index) const {
    if (index >= size()) return {};
    return JsonView(&(*mValue)[index], pointerTo(index), mIssues);
}

std::optional<uint64_t> JsonView::uintAt(size_t index) const {
    if (index >= size()) return std::nullopt;
    const Json& value = (*mValue)[index];
    std::optional<uint64_t> v = asUint(value);
    if (!v && mIssues) {
        mIssues->add(pointerTo(index), "expected a non-negative integer, got " + describe(value));
    }
    return v;
}

std::optional<std::string> JsonView::stringAt(size_t index) const {
    if (index >= size()) return std::nullopt;
    const Json& value = (*mValue)[index];
    if (!value.is_string()) {
        if (mIssues) {
            mIssues->add(pointerTo(index), "expected a string, got " + jsonTypeName(value));
        }
        return std::nullopt;
    }
    return value.get<std::string>();
}

const std::vector<std::string>& gltfCollections() {
    static const std::vector<std::string> kCollections = {
        "accessors", "animations", "buffers",  "bufferViews", "cameras", "images",  "materials",
        "meshes",    "nodes",      "samplers", "scenes",      "skins",   "textures"};
    return kCollections;
}

const Json* GltfJson::collection(std::string_view name) const {
    if (!mRoot->is_object()) return nullptr;
    auto it = mRoot->find(name);
    if (it == mRoot->end() || !it->is_array()) return nullptr;
    return &*it;
}

size_t GltfJson::count(std::string_view name) const {
    const Json* array = collection(name);
    return array ? array->size() : 0;
}

JsonView GltfJson::entity(std::string_view name, size_t index) const {
    const Json* array = collection(name);
    if (!array || index >= array->size() || !(*array)[index].is_object()) return {};
    return JsonView(&(*array)[index], "/" + std::string(name) + "/" + std::to_string(index),
                    mIssues);
}

const Json* GltfJson::lightArray() const {
    if (!mRoot->is_object()) return nullptr;
    auto ext = mRoot->find("extensions");
    if (ext == mRoot->end() || !ext->is_object()) return nullptr;
    auto khr = ext->find("KHR_lights_punctual");
    if (khr == ext->end() || !khr->is_object()) return nullptr;
    auto lights = khr->find("lights");
    if (lights == khr->end() || !lights->is_array()) return nullptr;
    return &*lights;
}

size_t GltfJson::lightCount() const {
    const Json* lights = lightArray();
    return lights ? lights->size() : 0;
}

JsonView GltfJson::light(size_t index) const {
    const Json* lights = lightArray();
    if (!lights || index >= lights->size() || !(*lights)[index].is_object()) return {};
    return JsonView(&(*lights)[index],
                    "/extensions/KHR_lights_punctual/lights/" + std::to_string(index), mIssues);
}

void GltfJson::checkCollections() const {
    JsonView root = rootView();
    for (const std::string& name : gltfCollections()) {
        JsonView array = root.array(name);  // records a non-array
        for (size_t i = 0; i < array.size(); ++i) {
            JsonView element = array.element(i);
            if (!element.isObject())
                element.issue("expected an object, got " + jsonTypeName(*element.raw()));
        }
    }
    JsonView lights = root.object("extensions").object("KHR_lights_punctual").array("lights");
    for (size_t i = 0; i < lights.size(); ++i) {
        JsonView element = lights.element(i);
        if (!element.isObject())
            element.issue("expected an object, got " + jsonTypeName(*element.raw()));
    }
}

bool percentDecode(std::string_view uri, std::string& out) {
    out.clear();
    out.reserve(uri.size());
    auto hex = [](char c) -> int {
        if (c >= '0' && c <= '9') return c - '0';
        if (c >= 'a' && c <= 'f') return c - 'a' + 10;
        if (c >= 'A' && c <= 'F') return c - 'A' + 10;
        return -1;
    };
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] != '%') {
            out += uri[i];
            continue;
        }
        if (i + 2 >= uri.size()) return false;
        int hi = hex(uri[i + 1]), lo = hex(uri[i + 2]);
        if (hi < 0 || lo < 0) return false;
        out += char(hi * 16 + lo);
        i += 2;
    }
    return true;
}

}  // namespace fovea::scene::gltf
