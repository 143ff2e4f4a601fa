// In-memory form of a graph file (docs/graph-format.md): what the user wrote, checked for
// structure only. Whether pass types, fields and parameters exist is the compiler's business; the
// `pointer` members let it report those errors at the right place in the file.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fovea::graph {

constexpr int kGraphFormatVersion = 1;
// Longest history an edge may ask for; each frame of delay costs one copy of the resource.
constexpr uint32_t kMaxEdgeDelay = 8;
// Largest width/height accepted in defaults.size (the Vulkan-guaranteed 2D image limit).
constexpr uint32_t kMaxImageSize = 16384;

// Equality on the descriptions below compares content only: `pointer` and `file` record where a
// value was read from, so a graph built in code equals the same graph parsed from disk.

// "pass.field": one field (input or output) of one pass.
struct Endpoint {
    std::string pass;
    std::string field;
    std::string str() const;  // "pass.field"
    bool operator==(const Endpoint&) const = default;
};

struct PassDesc {
    std::string name;
    std::string type;
    nlohmann::json params = nlohmann::json::object();
    bool enabled = true;
    std::string pointer;  // "/passes/2"
    bool operator==(const PassDesc& other) const;
};

struct EdgeDesc {
    Endpoint from;
    Endpoint to;
    uint32_t delay = 0;   // frames of history: 0 = this frame's value
    std::string pointer;  // "/edges/0"
    bool operator==(const EdgeDesc& other) const;
};

// Execution-order-only edge: `before` runs before `after`, no data flows.
struct OrderDesc {
    std::string before;
    std::string after;
    std::string pointer;  // "/order/0"
    bool operator==(const OrderDesc& other) const;
};

struct OutputDesc {
    Endpoint source;
    std::string pointer;  // "/outputs/0"
    bool operator==(const OutputDesc& other) const;
};

// Values the CLI flags --size, --frames, --seed, --scene override; unset = the tool's default.
struct GraphDefaults {
    std::optional<std::array<uint32_t, 2>> size;  // width, height
    std::optional<uint32_t> frames;
    std::optional<uint64_t> seed;
    std::optional<std::string> scene;
    std::optional<std::string> camera;  // camera path file, relative to the graph file
    std::optional<bool> stereo;         // side-by-side stereo rig (seed 000 §3.1)
    // "perspective" or "equirect" (the 360° camera of seed 003 P4; docs/camera-path.md)
    std::optional<std::string> cameraModel;
    bool operator==(const GraphDefaults&) const = default;
};

struct GraphDesc {
    int version = kGraphFormatVersion;
    std::string name;
    std::string description;
    std::string file;  // label used in errors (the path as given)
    GraphDefaults defaults;
    std::vector<PassDesc> passes;
    std::vector<EdgeDesc> edges;
    std::vector<OrderDesc> order;
    std::vector<OutputDesc> outputs;
    nlohmann::json editor;  // opaque, ignored by the compiler, preserved on save

    const PassDesc* findPass(std::string_view name) const;
    std::vector<std::string> passNames() const;
    bool operator==(const GraphDesc& other) const;
};

// Pass names: [A-Za-z_][A-Za-z0-9_]* (so "pass.field" and "--set pass.param=v" split cleanly).
bool isValidPassName(std::string_view name);
// "pass.field" with both halves valid names; nullopt otherwise.
std::optional<Endpoint> parseEndpoint(std::string_view text);

// Unreadable file -> InputError(path, "", "cannot read file: <strerror>").
GraphDesc parseGraphFile(const std::filesystem::path& path);
GraphDesc parseGraphText(std::string_view text, const std::string& fileLabel);
// For JSON already in memory (e.g. from an editor); same checks as parseGraphText.
GraphDesc parseGraphJson(const nlohmann::json& root, const std::string& fileLabel);

// Canonical form: defaults omitted, editor block kept; parseGraphJson(graphToJson(g)) == g.
// (nlohmann::json sorts keys; graphToText/saveGraphFile use the documented reading order.)
nlohmann::json graphToJson(const GraphDesc& graph);
// Canonical text: 2-space indent, fixed key order, trailing newline.
std::string graphToText(const GraphDesc& graph);
// Validates by re-parsing before writing (never writes a file that would not load), and refuses
// to replace an existing file unless `overwrite`; both failures are InputError.
void saveGraphFile(const GraphDesc& graph, const std::filesystem::path& path, bool overwrite);

}  // namespace fovea::graph
