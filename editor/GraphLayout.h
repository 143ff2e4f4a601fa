// Where the inspector draws a compiled graph: one box per pass with its input slots on the left
// and output slots on the right, columns left to right by the longest chain of same-frame edges
// (and `order` constraints) leading to the pass, rows by compiled execution order. A pure
// function of the plan (no window, no GPU), so it is unit-tested on every shipped graph.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/graph/GraphPlan.h"

namespace fovea::editor {

struct LayoutSlot {
    std::string field;
    float x = 0, y = 0;  // centre of the slot's circle, graph-view coordinates
};

struct LayoutNode {
    std::string name, type;
    int column = 0, row = 0;
    float x = 0, y = 0, width = 0, height = 0;  // box, top-left origin
    std::vector<LayoutSlot> inputs, outputs;    // reflection order; internals are not drawn
};

struct LayoutEdge {
    size_t fromNode = 0, fromSlot = 0;  // output slot of the producer
    size_t toNode = 0, toSlot = 0;      // input slot of the consumer
    uint32_t delay = 0;                 // > 0: a history edge, drawn distinctly
};

struct LayoutMetrics {
    float nodeWidth = 170, header = 22, slotPitch = 17, columnGap = 70, rowGap = 18, margin = 12;
};

struct GraphLayout {
    std::vector<LayoutNode> nodes;  // parallel to plan.nodes
    std::vector<LayoutEdge> edges;  // one per connected input
    float width = 0, height = 0;    // extent including the margin
};

// Node positions (top-left, graph-view coordinates) by pass name, as saved in the graph file's
// `editor` block: {"nodes": {"<pass>": [x, y], ...}} (docs/inspector.md, "Save as").
using NodePositions = std::map<std::string, std::array<float, 2>>;

// Nodes named in `positions` are placed there (negative coordinates clamp to 0); the others
// follow the layered layout. The extent covers every node.
GraphLayout layoutGraph(const graph::CompiledPlan& plan, const LayoutMetrics& metrics = {},
                        const NodePositions* positions = nullptr);

// Reads editor.nodes; an entry that is not [x, y] with finite numbers is skipped and described
// in `problems` ("editor.nodes.tm: expected [x, y]"), so a hand-edited block never stops a load.
NodePositions readNodePositions(const nlohmann::json& editorBlock, std::string& problems);
// The editor block with "nodes" replaced by every node's position in `layout` (other keys kept).
nlohmann::json writeNodePositions(nlohmann::json editorBlock, const GraphLayout& layout);

}  // namespace fovea::editor
