// GraphDesc helpers, file I/O and the canonical (saved) form. Parsing is in GraphDescParse.cpp.
#include "core/graph/GraphDesc.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/util/Error.h"
#include "core/util/UserFile.h"

namespace fovea::graph {

std::string Endpoint::str() const {
    return pass + "." + field;
}

bool PassDesc::operator==(const PassDesc& other) const {
    return name == other.name && type == other.type && params == other.params &&
           enabled == other.enabled;
}

bool EdgeDesc::operator==(const EdgeDesc& other) const {
    return from == other.from && to == other.to && delay == other.delay;
}

bool OrderDesc::operator==(const OrderDesc& other) const {
    return before == other.before && after == other.after;
}

bool OutputDesc::operator==(const OutputDesc& other) const {
    return source == other.source;
}

bool GraphDesc::operator==(const GraphDesc& other) const {
    return version == other.version && name == other.name && description == other.description &&
           defaults == other.defaults && passes == other.passes && edges == other.edges &&
           order == other.order && outputs == other.outputs && editor == other.editor;
}

const PassDesc* GraphDesc::findPass(std::string_view passName) const {
    for (const PassDesc& pass : passes) {
        if (pass.name == passName) return &pass;
    }
    return nullptr;
}

std::vector<std::string> GraphDesc::passNames() const {
    std::vector<std::string> names;
    names.reserve(passes.size());
    for (const PassDesc& pass : passes) names.push_back(pass.name);
    return names;
}

bool isValidPassName(std::string_view name) {
    if (name.empty()) return false;
    auto isAlpha = [](char c) {
        return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
    };
    if (!isAlpha(name[0])) return false;
    for (char c : name) {
        if (!isAlpha(c) && !(c >= '0' && c <= '9')) return false;
    }
    return true;
}

std::optional<Endpoint> parseEndpoint(std::string_view text) {
    size_t dot = text.find('.');
    if (dot == std::string_view::npos) return std::nullopt;
    Endpoint endpoint{std::string(text.substr(0, dot)), std::string(text.substr(dot + 1))};
    // Field names follow the pass-name rule, which also rules out a second '.'.
    if (!isValidPassName(endpoint.pass) || !isValidPassName(endpoint.field)) return std::nullopt;
    return endpoint;
}

namespace {

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

std::string errnoText(int error) {
    return std::strerror(error);
}

}  // namespace

GraphDesc parseGraphFile(const std::filesystem::path& path) {
    // Regular files only, up to kMaxJsonFileBytes: /dev/zero or a FIFO would never end.
    return parseGraphText(readUserTextFile(path, kMaxJsonFileBytes, "file"), path.string());
}

// --- canonical form -----------------------------------------------------------------------------

namespace {

// Built as ordered_json so the saved file reads top-down: identity, defaults, passes, wiring.
nlohmann::ordered_json toOrderedJson(const GraphDesc& graph) {
    nlohmann::ordered_json root;
    root["version"] = graph.version;
    if (!graph.name.empty()) root["name"] = graph.name;
    if (!graph.description.empty()) root["description"] = graph.description;

    nlohmann::ordered_json defaults = nlohmann::ordered_json::object();
    if (graph.defaults.size) defaults["size"] = *graph.defaults.size;
    if (graph.defaults.frames) defaults["frames"] = *graph.defaults.frames;
    if (graph.defaults.seed) defaults["seed"] = *graph.defaults.seed;
    if (graph.defaults.scene) defaults["scene"] = *graph.defaults.scene;
    if (graph.defaults.camera) defaults["camera"] = *graph.defaults.camera;
    if (graph.defaults.stereo) defaults["stereo"] = *graph.defaults.stereo;
    if (graph.defaults.cameraModel) defaults["camera_model"] = *graph.defaults.cameraModel;
    if (!defaults.empty()) root["defaults"] = defaults;

    nlohmann::ordered_json passes = nlohmann::ordered_json::array();
    for (const PassDesc& pass : graph.passes) {
        nlohmann::ordered_json entry;
        entry["name"] = pass.name;
        entry["type"] = pass.type;
        // A null params (graph built in code) means "none", like an empty object.
        if (!pass.params.is_null() && !(pass.params.is_object() && pass.params.empty())) {
            entry["params"] = nlohmann::ordered_json(pass.params);
        }
        if (!pass.enabled) entry["enabled"] = false;
        passes.push_back(std::move(entry));
    }
    root["passes"] = std::move(passes);

    if (!graph.edges.empty()) {
        nlohmann::ordered_json edges = nlohmann::ordered_json::array();
        for (const EdgeDesc& edge : graph.edges) {
            nlohmann::ordered_json entry;
            entry["from"] = edge.from.str();
            entry["to"] = edge.to.str();
            if (edge.delay != 0) entry["delay"] = edge.delay;
            edges.push_back(std::move(entry));
        }
        root["edges"] = std::move(edges);
    }
    if (!graph.order.empty()) {
        nlohmann::ordered_json order = nlohmann::ordered_json::array();
        for (const OrderDesc& entry : graph.order) {
            order.push_back({{"before", entry.before}, {"after", entry.after}});
        }
        root["order"] = std::move(order);
    }
    if (!graph.outputs.empty()) {
        nlohmann::ordered_json outputs = nlohmann::ordered_json::array();
        for (const OutputDesc& output : graph.outputs) outputs.push_back(output.source.str());
        root["outputs"] = std::move(outputs);
    }
    if (!graph.editor.is_null()) root["editor"] = nlohmann::ordered_json(graph.editor);
    return root;
}

}  // namespace

nlohmann::json graphToJson(const GraphDesc& graph) {
    return nlohmann::json(toOrderedJson(graph));
}

std::string graphToText(const GraphDesc& graph) {
    return toOrderedJson(graph).dump(2) + "\n";
}

void saveGraphFile(const GraphDesc& graph, const std::filesystem::path& path, bool overwrite) {
    const std::string label = path.string();
    const std::string text = graphToText(graph);
    parseGraphText(text, label);  // throws with a pointer into the file we were about to write
    std::error_code error;
    if (!overwrite && std::filesystem::exists(path, error)) {
        throw InputError(label, "", "file already exists (not overwriting it)");
    }
    // Write a sibling temporary and rename it over the target, so an interrupted save never
    // leaves a truncated graph behind.
    const std::string temporary = label + ".tmp";
    {
        errno = 0;
        FilePtr file(std::fopen(temporary.c_str(), "wb"));
        if (!file) throw InputError(label, "", "cannot write file: " + errnoText(errno));
        bool ok = std::fwrite(text.data(), 1, text.size(), file.get()) == text.size();
        int writeErrno = errno;
        ok = std::fclose(file.release()) == 0 && ok;
        if (!ok) {
            std::filesystem::remove(temporary, error);
            throw InputError(label, "",
                             "cannot write file: " + errnoText(writeErrno ? writeErrno : errno));
        }
    }
    std::filesystem::rename(temporary, path, error);
    if (error) {
        std::string reason = error.message();
        std::filesystem::remove(temporary, error);
        throw InputError(label, "", "cannot write file: " + reason);
    }
}

}  // namespace fovea::graph
