// Where the inspector draws a compiled graph: one box per pass with its input slots on the left
// and output slots on the right, columns left to right by the longest chain of same-frame edges
// (and `order` constraints) leading to the pass, rows by compiled execution order. A pure
// function of the plan (no window, no GPU), so it is unit-tested on every shipped graph.
#pragma once
#include <cstddef>
#include <cstdint>
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

GraphLayout layoutGraph(const graph::CompiledPlan& plan, const LayoutMetrics& metrics = {});

}  // namespace fovea::editor
