#include "editor/GraphLayout.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace fovea::editor {

namespace {

// Longest-path depth over same-frame edges and order constraints. The compiler rejects cycles
// that do not pass a delayed edge (checkEdges), so this graph is a DAG; `visiting` still guards
// the recursion so a plan that slipped through cannot overflow the stack.
std::vector<int> columnsOf(const graph::CompiledPlan& plan) {
    const size_t n = plan.nodes.size();
    std::vector<std::vector<size_t>> predecessors(n);
    for (const auto& [key, source] : plan.inputs)
        if (source.delay == 0 && source.node < n) predecessors[key.first].push_back(source.node);
    for (const auto& [before, after] : plan.orderEdges)
        if (before < n && after < n) predecessors[after].push_back(before);
    std::vector<int> column(n, -1);
    std::vector<bool> visiting(n, false);
    std::function<int(size_t)> depth = [&](size_t node) -> int {
        if (column[node] >= 0) return column[node];
        if (visiting[node]) return 0;
        visiting[node] = true;
        int d = 0;
        for (size_t p : predecessors[node]) d = std::max(d, depth(p) + 1);
        visiting[node] = false;
        return column[node] = d;
    };
    for (size_t i = 0; i < n; ++i) depth(i);
    return column;
}

size_t slotIndex(const std::vector<LayoutSlot>& slots, const std::string& field) {
    for (size_t i = 0; i < slots.size(); ++i)
        if (slots[i].field == field) return i;
    return graph::kNone;
}

}  // namespace

GraphLayout layoutGraph(const graph::CompiledPlan& plan, const LayoutMetrics& m,
                        const NodePositions* positions) {
    GraphLayout layout;
    const size_t n = plan.nodes.size();
    layout.nodes.resize(n);
    const std::vector<int> column = columnsOf(plan);

    // Rows: alive passes by execution position, then culled ones in graph-file order.
    std::vector<size_t> byOrder(n);
    for (size_t i = 0; i < n; ++i) byOrder[i] = i;
    auto rank = [&](size_t i) {
        const int position = plan.positionOf(i);
        return position >= 0 ? size_t(position) : n + i;
    };
    std::stable_sort(byOrder.begin(), byOrder.end(),
                     [&](size_t a, size_t b) { return rank(a) < rank(b); });

    const int columns = n ? *std::max_element(column.begin(), column.end()) + 1 : 0;
    std::vector<float> nextY(size_t(columns), m.margin);
    std::vector<int> rows(size_t(columns), 0);
    for (size_t i : byOrder) {
        const graph::PassNode& pn = plan.nodes[i];
        LayoutNode& node = layout.nodes[i];
        node.name = pn.name;
        node.type = pn.type;
        node.column = column[i];
        node.row = rows[size_t(node.column)]++;
        for (const auto& field : pn.reflection.fields()) {
            if (field.kind == graph::FieldKind::Input) node.inputs.push_back({field.name});
            if (field.kind == graph::FieldKind::Output) node.outputs.push_back({field.name});
        }
        const size_t slots = std::max<size_t>({node.inputs.size(), node.outputs.size(), 1});
        node.width = m.nodeWidth;
        node.height = m.header + float(slots) * m.slotPitch + m.slotPitch * 0.5f;
        node.x = m.margin + float(node.column) * (m.nodeWidth + m.columnGap);
        node.y = nextY[size_t(node.column)];
        if (auto saved = positions ? positions->find(node.name) : NodePositions::const_iterator{};
            positions && saved != positions->end()) {
            node.x = std::max(0.0f, saved->second[0]);
            node.y = std::max(0.0f, saved->second[1]);
        } else {
            nextY[size_t(node.column)] = node.y + node.height + m.rowGap;
        }
        for (size_t s = 0; s < node.inputs.size(); ++s)
            node.inputs[s] = {node.inputs[s].field, node.x,
                              node.y + m.header + (float(s) + 0.5f) * m.slotPitch};
        for (size_t s = 0; s < node.outputs.size(); ++s)
            node.outputs[s] = {node.outputs[s].field, node.x + node.width,
                               node.y + m.header + (float(s) + 0.5f) * m.slotPitch};
        layout.width = std::max(layout.width, node.x + node.width + m.margin);
        layout.height = std::max(layout.height, node.y + node.height + m.margin);
    }

    for (const auto& [key, source] : plan.inputs) {
        if (source.node >= n) continue;  // an unconnected optional input
        LayoutEdge edge;
        edge.fromNode = source.node;
        edge.toNode = key.first;
        edge.fromSlot = slotIndex(layout.nodes[source.node].outputs, source.field);
        edge.toSlot = slotIndex(layout.nodes[key.first].inputs, key.second);
        edge.delay = source.delay;
        if (edge.fromSlot != graph::kNone && edge.toSlot != graph::kNone)
            layout.edges.push_back(edge);
    }
    return layout;
}

NodePositions readNodePositions(const nlohmann::json& editorBlock, std::string& problems) {
    NodePositions out;
    if (!editorBlock.is_object() || !editorBlock.contains("nodes")) return out;
    const nlohmann::json& nodes = editorBlock["nodes"];
    if (!nodes.is_object()) {
        problems += "editor.nodes: expected an object {\"<pass>\": [x, y]}\n";
        return out;
    }
    for (const auto& [name, value] : nodes.items()) {
        const bool ok = value.is_array() && value.size() == 2 && value[0].is_number() &&
                        value[1].is_number() && std::isfinite(value[0].get<double>()) &&
                        std::isfinite(value[1].get<double>());
        if (!ok) {
            problems += "editor.nodes." + name + ": expected [x, y] (finite numbers)\n";
            continue;
        }
        out[name] = {value[0].get<float>(), value[1].get<float>()};
    }
    return out;
}

nlohmann::json writeNodePositions(nlohmann::json editorBlock, const GraphLayout& layout) {
    if (!editorBlock.is_object()) editorBlock = nlohmann::json::object();
    nlohmann::json nodes = nlohmann::json::object();
    // Whole pixels: the file stays readable and a load gives back exactly what was saved.
    for (const LayoutNode& n : layout.nodes) nodes[n.name] = {std::round(n.x), std::round(n.y)};
    editorBlock["nodes"] = nodes;
    return editorBlock;
}

}  // namespace fovea::editor
