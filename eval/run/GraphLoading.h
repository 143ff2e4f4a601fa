// A graph file as every command loads it: parsed, with its --set overrides applied and checked
// against the pass's declared parameters (errors name the flag), and its render size.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"

namespace fovea::eval {

struct GraphOptions {
    std::string graph;
    std::string size;               // "WxH", empty = graph default
    std::vector<std::string> sets;  // pass.param=value
    bool noAliasing = false;
};

// Parses the graph file and applies the --set overrides; errors name the file and pointer, or
// the flag.
graph::GraphDesc loadGraph(const GraphOptions& options);
// "256x128" -> {256, 128}; errors name `flag`.
std::array<uint32_t, 2> parseSize(const std::string& text, const std::string& flag);
// Render size from --size or the graph's defaults (256x256 when neither gives one).
std::array<uint32_t, 2> renderSize(const GraphOptions& options, const graph::GraphDesc& desc);

}  // namespace fovea::eval
