#include "editor/ParamWidgets.h"

#include <imgui.h>

#include <array>
#include <cmath>

#include "core/graph/Pass.h"

namespace fovea::editor {

namespace {

bool finiteRange(const graph::ParamRange& r) {
    return std::isfinite(r.min) && std::isfinite(r.max) && r.max > r.min;
}

void tooltip(const graph::ParamSpec& spec) {
    if (!ImGui::IsItemHovered()) return;
    std::string text = spec.doc;
    if (std::isfinite(spec.range.min) || std::isfinite(spec.range.max))
        text +=
            "\nrange " + std::to_string(spec.range.min) + " .. " + std::to_string(spec.range.max);
    ImGui::SetTooltip("%s", text.c_str());
}

class WidgetVisitor : public graph::ParamVisitor {
public:
    std::optional<ParamChange> change;

    void visit(const graph::ParamSpec& spec, bool& value, bool) override {
        bool v = value;
        if (ImGui::Checkbox(spec.name.c_str(), &v)) change = ParamChange{spec.name, v};
        tooltip(spec);
    }
    void visit(const graph::ParamSpec& spec, int& value, int) override {
        int v = value;
        bool edited = false;
        if (finiteRange(spec.range) && spec.range.max - spec.range.min <= 4096)
            edited =
                ImGui::SliderInt(spec.name.c_str(), &v, int(spec.range.min), int(spec.range.max));
        else
            edited =
                ImGui::InputInt(spec.name.c_str(), &v, 1, 16, ImGuiInputTextFlags_EnterReturnsTrue);
        if (edited && v != value) change = ParamChange{spec.name, v};
        tooltip(spec);
    }
    void visit(const graph::ParamSpec& spec, float& value, float) override {
        float v = value;
        bool edited = false;
        if (finiteRange(spec.range))
            edited = ImGui::SliderFloat(spec.name.c_str(), &v, float(spec.range.min),
                                        float(spec.range.max));
        else
            edited = ImGui::InputFloat(spec.name.c_str(), &v, 0.0f, 0.0f, "%.4g",
                                       ImGuiInputTextFlags_EnterReturnsTrue);
        if (edited && v != value) change = ParamChange{spec.name, v};
        tooltip(spec);
    }
    void visit(const graph::ParamSpec& spec, std::string& value, const std::string&) override {
        if (!spec.choices.empty()) {
            if (ImGui::BeginCombo(spec.name.c_str(), value.c_str())) {
                for (const auto& choice : spec.choices)
                    if (ImGui::Selectable(choice.c_str(), choice == value) && choice != value)
                        change = ParamChange{spec.name, choice};
                ImGui::EndCombo();
            }
        } else {
            std::array<char, 256> buffer{};
            value.copy(buffer.data(), buffer.size() - 1);
            if (ImGui::InputText(spec.name.c_str(), buffer.data(), buffer.size(),
                                 ImGuiInputTextFlags_EnterReturnsTrue))
                change = ParamChange{spec.name, std::string(buffer.data())};
        }
        tooltip(spec);
    }
    void visit(const graph::ParamSpec& spec, glm::vec3& value, const glm::vec3&) override {
        float v[3] = {value.x, value.y, value.z};
        if (ImGui::InputFloat3(spec.name.c_str(), v, "%.4g", ImGuiInputTextFlags_EnterReturnsTrue))
            change = ParamChange{spec.name, nlohmann::json::array({v[0], v[1], v[2]})};
        tooltip(spec);
    }
};

}  // namespace

std::optional<ParamChange> drawParamWidgets(graph::Pass& pass) {
    WidgetVisitor visitor;
    ImGui::PushID(pass.name().c_str());
    pass.params(visitor);
    ImGui::PopID();
    return visitor.change;
}

}  // namespace fovea::editor
