// The parameters panel: one ImGui widget per parameter a pass declares (ParamVisitor, so the
// widget follows the declaration: type, range, choices, doc as tooltip). Widgets never write the
// live pass: a change is returned as JSON and goes through the graph description and a rebuild.
#pragma once
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace fovea::graph {
class Pass;
}

namespace fovea::editor {

struct ParamChange {
    std::string name;
    nlohmann::json value;
};

// Draws the widgets of `pass` (current values) and returns the parameter the user changed this
// frame, if any. Needs an ImGui frame in progress.
std::optional<ParamChange> drawParamWidgets(graph::Pass& pass);

}  // namespace fovea::editor
