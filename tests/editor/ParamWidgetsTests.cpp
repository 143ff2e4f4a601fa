// The parameters panel without a window or GPU (ImGui's null-backend pattern: font atlas,
// display size, mouse state, NewFrame .. Render): widgets come from the pass's ParamVisitor
// declaration, and a click on one becomes a typed change of that parameter.
#include <gtest/gtest.h>
#include <imgui.h>

#include "core/graph/Param.h"
#include "core/graph/Pass.h"
#include "core/graph/PassRegistry.h"
#include "editor/ParamWidgets.h"
#include "passes/RegisterPasses.h"

namespace fovea::editor {
namespace {

class ImGuiFrames {
public:
    ImGuiFrames() {
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;
        io.DisplaySize = ImVec2(600, 400);
        io.DeltaTime = 1.0f / 60.0f;
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);  // builds the atlas (no texture needed)
    }
    ~ImGuiFrames() { ImGui::DestroyContext(); }

    // One frame with the mouse at `mouse` (button 0 down or not); returns the change, the rect
    // of the last widget and the number of vertices drawn.
    std::optional<ParamChange> frame(graph::Pass& pass, ImVec2 mouse, bool down, ImVec4* last,
                                     int* vertices) {
        ImGuiIO& io = ImGui::GetIO();
        io.MousePos = mouse;
        io.MouseDown[0] = down;
        ImGui::NewFrame();
        ImGui::SetNextWindowPos(ImVec2(0, 0));
        ImGui::SetNextWindowSize(ImVec2(600, 400));
        ImGui::Begin("params");
        auto change = drawParamWidgets(pass);
        const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
        *last = ImVec4(a.x, a.y, b.x, b.y);
        ImGui::End();
        ImGui::Render();
        *vertices = ImGui::GetDrawData()->TotalVtxCount;
        return change;
    }
};

TEST(ParamWidgets, ClickOnTheLastDeclaredParameterChangesIt) {
    registerBuiltinPasses();
    // Tonemap declares exposure (float, range), operator (choices), srgb (bool) in that order.
    auto pass = graph::passRegistry().create("Tonemap", "tm");
    graph::applyParamDefaults(*pass);
    ImGuiFrames imgui;
    ImVec4 rect;
    int vertices = 0;
    const ImVec2 away(-1000, -1000);
    EXPECT_FALSE(imgui.frame(*pass, away, false, &rect, &vertices));
    EXPECT_GT(vertices, 0) << "nothing drawn";
    const ImVec2 box(rect.x + 6, (rect.y + rect.w) * 0.5f);          // the checkbox square
    EXPECT_FALSE(imgui.frame(*pass, box, false, &rect, &vertices));  // hover
    EXPECT_FALSE(imgui.frame(*pass, box, true, &rect, &vertices));   // press
    auto change = imgui.frame(*pass, box, false, &rect, &vertices);  // release = click
    ASSERT_TRUE(change);
    EXPECT_EQ(change->name, "srgb");
    EXPECT_EQ(change->value, nlohmann::json(false));  // default true, toggled, typed bool
    // The widget never writes the live pass: the change goes through the graph description.
    EXPECT_EQ(graph::saveParams(*pass, true), nlohmann::json::object());
}

}  // namespace
}  // namespace fovea::editor
