// The inspector's three windows: the graph (ImDrawList, GraphLayout), the preview rectangle and
// its controls, and the side panel (controls, errors, timings, parameters of the selected pass).
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/graph/PassRegistry.h"
#include "core/image/ImageIO.h"
#include "core/vk/Context.h"
#include "editor/Inspector.h"
#include "editor/ParamWidgets.h"

namespace fovea::editor {

std::array<uint8_t, 3> statusColour(graph::PassStatus status) {
    switch (status) {
        case graph::PassStatus::Executed:
            return {64, 150, 72};
        case graph::PassStatus::Cached:
            return {56, 104, 190};
        case graph::PassStatus::Culled:
            return {96, 96, 96};
        case graph::PassStatus::Bypassed:
            return {196, 160, 40};
        case graph::PassStatus::Skipped:
            return {150, 72, 170};
    }
    return {0, 0, 0};
}

namespace {

ImU32 colourOf(const std::array<uint8_t, 3>& c, uint8_t alpha = 255) {
    return IM_COL32(c[0], c[1], c[2], alpha);
}

// Distance from `p` to a cubic Bezier, sampled at 32 points (edges are short, clicks coarse).
float bezierDistance(ImVec2 a, ImVec2 c1, ImVec2 c2, ImVec2 b, ImVec2 p) {
    float best = FLT_MAX;
    for (int i = 0; i <= 32; ++i) {
        const float t = float(i) / 32.0f, u = 1.0f - t;
        const float w0 = u * u * u, w1 = 3 * u * u * t, w2 = 3 * u * t * t, w3 = t * t * t;
        const float x = w0 * a.x + w1 * c1.x + w2 * c2.x + w3 * b.x;
        const float y = w0 * a.y + w1 * c1.y + w2 * c2.y + w3 * b.y;
        best = std::min(best, std::hypot(x - p.x, y - p.y));
    }
    return best;
}

constexpr ImU32 kEdgeColour = IM_COL32(200, 200, 210, 200);
constexpr ImU32 kDelayEdgeColour = IM_COL32(255, 140, 30, 230);  // history edges stand out

}  // namespace

void Inspector::drawUi() {
    const ImVec2 size = ImGui::GetIO().DisplaySize;
    const float graphHeight = std::floor(size.y * 0.42f), previewWidth = std::floor(size.x * 0.55f);
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(size.x, graphHeight));
    ImGui::Begin("Graph", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    drawGraphView();
    ImGui::End();
    ImGui::SetNextWindowPos(ImVec2(0, graphHeight));
    ImGui::SetNextWindowSize(ImVec2(previewWidth, size.y - graphHeight));
    // No background: the preview pixels are in the swapchain image under this window.
    ImGui::Begin("Preview", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                     ImGuiWindowFlags_NoBackground | ImGuiWindowFlags_NoScrollbar);
    drawPreviewPanel();
    ImGui::End();
    ImGui::SetNextWindowPos(ImVec2(previewWidth, graphHeight));
    ImGui::SetNextWindowSize(ImVec2(size.x - previewWidth, size.y - graphHeight));
    ImGui::Begin("Inspector", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    drawSidePanel();
    ImGui::End();
}

void Inspector::drawGraphView() {
    ImGui::BeginChild("canvas", ImVec2(0, 0), false, ImGuiWindowFlags_HorizontalScrollbar);
    const ImVec2 origin = ImGui::GetCursorScreenPos();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    mCanvasClip = {draw->GetClipRectMin().x, draw->GetClipRectMin().y, draw->GetClipRectMax().x,
                   draw->GetClipRectMax().y};
    // A click near an edge previews the field it carries (what its input reads, delay included).
    const bool clicked =
        ImGui::IsWindowHovered() && ImGui::IsMouseClicked(0) && !ImGui::IsAnyItemHovered();
    const std::string edgeHit = drawEdges(draw, origin, clicked);
    if (!edgeHit.empty()) previewField(edgeHit);

    mNodeRects.assign(mLayout.nodes.size(), {0, 0, 0, 0});
    bool moved = false;
    for (size_t i = 0; i < mLayout.nodes.size(); ++i) moved |= drawNode(draw, origin, i);
    ImGui::SetCursorScreenPos(origin);
    ImGui::Dummy(ImVec2(mLayout.width, mLayout.height));
    ImGui::EndChild();
    if (moved) relayout();
}

std::string Inspector::drawEdges(ImDrawList* draw, ImVec2 origin, bool clicked) const {
    auto at = [&](float x, float y) { return ImVec2(origin.x + x, origin.y + y); };
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    std::string edgeHit;
    float edgeHitDistance = 6.0f;  // pixels
    for (const LayoutEdge& e : mLayout.edges) {
        const LayoutSlot& from = mLayout.nodes[e.fromNode].outputs[e.fromSlot];
        const LayoutSlot& to = mLayout.nodes[e.toNode].inputs[e.toSlot];
        const ImVec2 a = at(from.x, from.y), b = at(to.x, to.y);
        const float bend = std::max(40.0f, std::abs(b.x - a.x) * 0.4f);
        const std::string carried = mLayout.nodes[e.toNode].name + "." + to.field;
        const bool shown = carried == mPreview;
        const ImU32 colour =
            shown ? IM_COL32(255, 230, 80, 255) : (e.delay ? kDelayEdgeColour : kEdgeColour);
        const ImVec2 c1(a.x + bend, a.y), c2(b.x - bend, b.y);
        draw->AddBezierCubic(a, c1, c2, b, colour, e.delay || shown ? 2.5f : 1.5f);
        if (clicked) {
            const float d = bezierDistance(a, c1, c2, b, mouse);
            if (d < edgeHitDistance) {
                edgeHitDistance = d;
                edgeHit = carried;
            }
        }
        if (e.delay) {
            const std::string label = "z^-" + std::to_string(e.delay);
            draw->AddText(ImVec2((a.x + b.x) * 0.5f, (a.y + b.y) * 0.5f - 14), colour,
                          label.c_str());
        }
    }
    return edgeHit;
}

bool Inspector::drawNode(ImDrawList* draw, ImVec2 origin, size_t i) {
    auto at = [&](float x, float y) { return ImVec2(origin.x + x, origin.y + y); };
    const auto& records = mSession.graph().records();
    const LayoutMetrics metrics;
    const LayoutNode& n = mLayout.nodes[i];
    const graph::PassStatus status =
        i < records.size() ? records[i].status : graph::PassStatus::Culled;
    const ImVec2 p0 = at(n.x, n.y), p1 = at(n.x + n.width, n.y + n.height);
    draw->AddRectFilled(p0, p1, IM_COL32(36, 36, 44, 240), 4.0f);
    draw->AddRectFilled(p0, ImVec2(p1.x, p0.y + metrics.header), colourOf(statusColour(status)),
                        4.0f, ImDrawFlags_RoundCornersTop);
    draw->AddRect(p0, p1,
                  n.name == mSelected ? IM_COL32(255, 255, 255, 255) : IM_COL32(90, 90, 100, 255),
                  4.0f, 0, n.name == mSelected ? 2.5f : 1.0f);
    const std::string title = n.name + " : " + n.type;
    draw->AddText(ImVec2(p0.x + 6, p0.y + 4), IM_COL32(255, 255, 255, 255), title.c_str());
    mNodeRects[i] = {p0.x, p0.y, n.width, metrics.header};

    bool moved = false;
    ImGui::SetCursorScreenPos(p0);
    ImGui::PushID(int(i));
    if (ImGui::InvisibleButton("node", ImVec2(n.width, metrics.header))) mSelected = n.name;
    // Dragging a header moves the node; "save as" writes the positions (editor block).
    if (ImGui::IsItemActive() && ImGui::IsMouseDragging(0)) {
        const ImVec2 d = ImGui::GetIO().MouseDelta;
        mPositions[n.name] = {n.x + d.x, n.y + d.y};
        moved = true;
    }
    if (ImGui::IsItemHovered()) {
        std::string tip = n.name + " (" + n.type + "): " + graph::passStatusName(status);
        if (i < records.size() && !records[i].reason.empty()) tip += "\n" + records[i].reason;
        if (i < records.size() && !records[i].gpuMs.empty())
            tip += "\nGPU " + std::to_string(records[i].gpuMs.back()) + " ms";
        ImGui::SetTooltip("%s", tip.c_str());
    }
    drawNodeSlots(draw, origin, n);
    ImGui::PopID();
    return moved;
}

void Inspector::drawNodeSlots(ImDrawList* draw, ImVec2 origin, const LayoutNode& n) {
    auto at = [&](float x, float y) { return ImVec2(origin.x + x, origin.y + y); };
    for (const LayoutSlot& s : n.inputs) {
        draw->AddCircleFilled(at(s.x, s.y), 4.0f, IM_COL32(170, 200, 255, 255));
        draw->AddText(at(s.x + 8, s.y - 7), IM_COL32(210, 210, 220, 255), s.field.c_str());
    }
    // An output's label is a button that previews it.
    for (const LayoutSlot& s : n.outputs) {
        const std::string resource = n.name + "." + s.field;
        const bool shown = resource == mPreview;
        draw->AddCircleFilled(at(s.x, s.y), shown ? 6.0f : 4.0f,
                              shown ? IM_COL32(255, 230, 80, 255) : IM_COL32(255, 200, 140, 255));
        const float w = ImGui::CalcTextSize(s.field.c_str()).x;
        draw->AddText(at(s.x - 8 - w, s.y - 7), IM_COL32(230, 220, 200, 255), s.field.c_str());
        ImGui::SetCursorScreenPos(at(s.x - 8 - w, s.y - 7));
        ImGui::PushID(s.field.c_str());
        if (ImGui::InvisibleButton("out", ImVec2(w + 14, 14))) {
            previewField(resource);
            mSelected = n.name;
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("preview %s", resource.c_str());
        ImGui::PopID();
    }
}

void Inspector::drawPreviewPanel() {
    ImGui::SetNextItemWidth(90);
    if (ImGui::BeginCombo("##channel", previewChannelName(mSettings.channel))) {
        for (int c = 0; c <= int(PreviewChannel::Luminance); ++c)
            if (ImGui::Selectable(previewChannelName(PreviewChannel(c)),
                                  int(mSettings.channel) == c))
                mSettings.channel = PreviewChannel(c);
        ImGui::EndCombo();
    }
    ImGui::SameLine();
    ImGui::SetNextItemWidth(110);
    ImGui::SliderFloat("EV", &mSettings.exposure, -10.0f, 10.0f, "%.1f");
    ImGui::SameLine();
    ImGui::Checkbox("false colour", &mSettings.falseColour);
    ImGui::SameLine();
    if (ImGui::Button("fit")) mSettings.view = {};
    ImGui::SameLine();
    ImGui::Text("x%.1f", double(mSettings.view.zoom));
    // The second image: any image output of a live pass, or the --reference file.
    ImGui::SetNextItemWidth(170);
    if (ImGui::BeginCombo("##compare", mCompare.empty() ? "compare: none" : mCompare.c_str())) {
        if (ImGui::Selectable("none", mCompare.empty())) compareWith("");
        if (mOptions.reference.width > 0 && ImGui::Selectable("reference", mCompare == "reference"))
            compareWith("reference");
        for (const auto& r : mSession.graph().plan().resources)
            if (r.isImage && ImGui::Selectable(r.name.c_str(), mCompare == r.name))
                compareWith(r.name);
        ImGui::EndCombo();
    }
    ImGui::SameLine();
    ImGui::Checkbox("difference", &mDifference);
    ImGui::SameLine();
    if (ImGui::Button("save preview")) savePreview("preview_" + std::to_string(mFrame) + ".exr");
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("writes preview_<frame>.exr (full float) in the working folder");
    std::string title = mPreview.empty() ? "(click an output slot or an edge)" : mPreview;
    if (!mCompare.empty())
        title += mDifference ? "  |  |" + mPreview + " - " + mCompare + "|" : "  |  " + mCompare;
    if (mDifference && !mCompare.empty() && mDifferenceImage.width == 0 && mCompareImage.width > 0)
        title += "  (sizes differ: " + std::to_string(mPreviewImage.width) + "x" +
                 std::to_string(mPreviewImage.height) + " vs " +
                 std::to_string(mCompareImage.width) + "x" + std::to_string(mCompareImage.height) +
                 ")";
    ImGui::TextUnformatted(title.c_str());
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    const ImVec2 pos = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("preview", ImVec2(std::max(avail.x, 1.0f), std::max(avail.y, 1.0f)),
                           ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
    handlePreviewMouse();
    mPreviewRect[0] = pos.x;
    mPreviewRect[1] = pos.y;
    mPreviewRect[2] = std::max(avail.x, 0.0f);
    mPreviewRect[3] = std::max(avail.y, 0.0f);
}

// Wheel: zoom around the pointer; left drag: pan; right drag: free-fly look (turns it on).
void Inspector::handlePreviewMouse() {
    const ImGuiIO& io = ImGui::GetIO();
    const ImVec2 mouse = io.MousePos;
    const PreviewFit& fit =
        mFitB.width > 0 && mouse.x - float(mBlit.x) >= float(mFitB.paneX) ? mFitB : mFit;
    if (ImGui::IsItemHovered() && io.MouseWheel != 0)
        zoomAround(mSettings.view, fit, std::exp2(io.MouseWheel * 0.25f), mouse.x - float(mBlit.x),
                   mouse.y - float(mBlit.y));
    if (ImGui::IsItemActive() && ImGui::IsMouseDragging(0))
        panBy(mSettings.view, fit, io.MouseDelta.x, io.MouseDelta.y);
    if (ImGui::IsItemActive() && ImGui::IsMouseDragging(1)) {
        setFreeFly(true);
        if (mFreeFly) mFreeFly->look(io.MouseDelta.x * 0.2f, -io.MouseDelta.y * 0.2f);
    }
}

void Inspector::drawSaveAs() {
    ImGui::SetNextItemWidth(200);
    char buffer[512];
    std::snprintf(buffer, sizeof(buffer), "%s", mSaveAsPath.c_str());
    if (ImGui::InputText("##saveas", buffer, sizeof(buffer))) mSaveAsPath = buffer;
    ImGui::SameLine();
    if (ImGui::Button("save as")) {
        if (std::filesystem::exists(mSaveAsPath))
            mConfirmOverwrite = true;  // never replace a file without asking
        else
            saveAs(mSaveAsPath, false);
    }
    if (mConfirmOverwrite) {
        ImGui::OpenPopup("replace?");
        mConfirmOverwrite = false;
    }
    if (ImGui::BeginPopupModal("replace?", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("'%s' exists. Replace it?", mSaveAsPath.c_str());
        if (ImGui::Button("replace")) {
            saveAs(mSaveAsPath, true);
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("cancel")) ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    }
}

void Inspector::applyGazeFromMouse(const std::pair<uint32_t, uint32_t>& px) {
    const glm::vec2 uv((float(px.first) + 0.5f) / float(mPreviewImage.width),
                       (float(px.second) + 0.5f) / float(mPreviewImage.height));
    Gaze gaze = mGaze.value_or(Gaze{glm::vec2(0.5f), glm::vec2(0.5f)});
    if (mSession.stereo()) {
        const int eye = uv.x < 0.5f ? 0 : 1;
        gaze[size_t(eye)] = glm::vec2(uv.x * 2.0f - float(eye), uv.y);
    } else {
        gaze = {uv, uv};
    }
    mGaze = gaze;
}

// The pixel under the mouse in either pane, with its value in A, B and |A - B|.
void Inspector::drawPixelValues() {
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    auto px = previewPixelAt(mBlit, mFit, mouse.x, mouse.y);
    if (!px) px = previewPixelAt(mBlit, mFitB, mouse.x, mouse.y);
    if (!px) return;
    auto show = [&](const char* label, const image::ImageRGBA& img) {
        if (px->first >= img.width || px->second >= img.height) return;
        const float* v = &img.pixels[(size_t(px->second) * img.width + px->first) * 4];
        ImGui::Text("%s (%u, %u) = %.4g %.4g %.4g %.4g", label, px->first, px->second, v[0], v[1],
                    v[2], v[3]);
    };
    show("A", mPreviewImage);
    if (!mCompare.empty()) {
        show("B", mCompareImage);
        if (mDifferenceImage.width > 0) show("|A-B|", mDifferenceImage);
    }
    if (mGazeFollowsMouse && px->first < mPreviewImage.width && px->second < mPreviewImage.height)
        applyGazeFromMouse(*px);
}

void Inspector::drawSidePanel() {
    const graph::RenderGraph& g = mSession.graph();
    ImGui::Text("frame %u  %s", unsigned(g.frameIndex()), mPaused ? "(paused)" : "");
    ImGui::SameLine();
    if (ImGui::Button(mPaused ? "resume" : "pause")) mPaused = !mPaused;
    ImGui::SameLine();
    if (ImGui::Button("step")) mStep = true;
    ImGui::SameLine();
    if (ImGui::Button("reset")) mSession.graph().reset();
    ImGui::SameLine();
    ImGui::Checkbox("gaze = mouse", &mGazeFollowsMouse);
    if (!mError.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(255, 110, 100, 255));
        ImGui::TextWrapped("%s", mError.c_str());
        ImGui::PopStyleColor();
    }
    bool freeFly = mFreeFly.has_value();
    if (ImGui::Checkbox("free-fly camera (WASD QE, right-drag)", &freeFly)) setFreeFly(freeFly);
    if (ImGui::IsItemHovered())
        ImGui::SetTooltip("off: the camera follows the graph's camera path");
    drawSaveAs();
    drawPixelValues();
    drawTimings();
    if (!mSelected.empty()) {
        const size_t node = g.plan().findNode(mSelected);
        if (node != graph::kNone && ImGui::CollapsingHeader(("Parameters: " + mSelected).c_str(),
                                                            ImGuiTreeNodeFlags_DefaultOpen)) {
            if (auto change = drawParamWidgets(*g.plan().nodes[node].pass))
                setParam(mSelected, change->name, change->value);
        }
    }
}

void Inspector::drawTimings() {
    const graph::RenderGraph& g = mSession.graph();
    if (!ImGui::CollapsingHeader("GPU time", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::Text("frame %.2f ms GPU  (record %.2f ms CPU)", mLastTiming.gpuMs,
                mLastTiming.recordCpuMs);
    if (!mFrameMsHistory.empty()) {
        std::vector<float> history(mFrameMsHistory.begin(), mFrameMsHistory.end());
        ImGui::PlotLines("##frames", history.data(), int(history.size()), 0, nullptr, 0.0f, FLT_MAX,
                         ImVec2(-1, 36));
    }
    // Only passes that ran in the last frame (executed, or copied through when bypassed) have a
    // time of that frame; a cached or skipped pass's last entry is from an earlier frame.
    auto lastMs = [&](size_t n) {
        const auto& r = g.records()[n];
        const bool ran =
            r.status == graph::PassStatus::Executed || r.status == graph::PassStatus::Bypassed;
        return ran && !r.gpuMs.empty() ? r.gpuMs.back() : 0.0;
    };
    double longest = 1e-6;
    for (size_t n : g.plan().order) longest = std::max(longest, lastMs(n));
    for (size_t n : g.plan().order) {
        const auto& r = g.records()[n];
        const double ms = lastMs(n);
        const std::string label = g.plan().nodes[n].name + "  " + std::to_string(ms).substr(0, 6) +
                                  " ms  " + graph::passStatusName(r.status);
        ImGui::PushStyleColor(ImGuiCol_PlotHistogram, colourOf(statusColour(r.status)));
        ImGui::ProgressBar(float(ms / longest), ImVec2(-1, 0), label.c_str());
        ImGui::PopStyleColor();
    }
    ImGui::Text("memory: transient %.1f MiB (%.1f without aliasing), persistent %.1f MiB",
                double(g.plan().transientBytes()) / 1048576.0,
                double(g.plan().transientBytesWithoutAliasing()) / 1048576.0,
                double(g.plan().persistentBytes()) / 1048576.0);
}

nlohmann::json Inspector::screenshotInfo(uint32_t width, uint32_t height) const {
    // What a test needs to find things in the picture: where the preview and every node header
    // were drawn, each node's status and colour, the comparison, camera and last change.
    nlohmann::json info;
    info["frame"] = mFrame;
    info["window"] = {width, height};
    info["preview"] = {{"resource", mPreview},
                       {"rect", {mBlit.x, mBlit.y, mBlit.width, mBlit.height}},
                       {"image", visibleImageRect(mBlit, mFit)},
                       {"zoom", mSettings.view.zoom}};
    info["compare"] = {{"resource", mCompare},
                       {"difference", mDifference && mDifferenceImage.width > 0},
                       {"image", visibleImageRect(mBlit, mFitB)}};
    info["camera"] = {{"mode", mFreeFly ? "freefly" : "path"}};
    if (mFreeFly) {
        const glm::vec3 p = mFreeFly->position();
        info["camera"]["position"] = {p.x, p.y, p.z};
    }
    if (!mChanges.empty()) {
        const AppliedChange& c = mChanges.back();
        info["last_change"] = {{"what", c.what},
                               {"ms", c.ms},
                               {"in_place", c.result.inPlace},
                               {"recompiled", c.result.recompiled},
                               {"pipelines_created", c.result.pipelinesCreated},
                               {"pipelines_reused", c.result.pipelinesReused}};
    }
    info["selected"] = mSelected;
    info["error"] = mError;
    const auto& records = mSession.graph().records();
    info["nodes"] = nlohmann::json::array();
    for (size_t i = 0; i < mLayout.nodes.size() && i < mNodeRects.size(); ++i) {
        const auto status = i < records.size() ? records[i].status : graph::PassStatus::Culled;
        const auto c = statusColour(status);
        const auto& r = mNodeRects[i];
        info["nodes"].push_back(
            {{"name", mLayout.nodes[i].name},
             {"status", graph::passStatusName(status)},
             {"reason", i < records.size() ? records[i].reason : ""},
             {"header", mNodeRects[i]},
             {"position", {mLayout.nodes[i].x, mLayout.nodes[i].y}},
             {"visible", r[0] >= mCanvasClip[0] && r[1] >= mCanvasClip[1] &&
                             r[0] + r[2] <= mCanvasClip[2] && r[1] + r[3] <= mCanvasClip[3]},
             {"colour", {c[0], c[1], c[2]}}});
    }
    return info;
}

void Inspector::writeScreenshot(const std::string& path, const image::ImageRGBA& pixels) const {
    image::writePng(path, pixels, image::PngEncoding::AsIs);
    std::ofstream(path + ".json") << screenshotInfo(pixels.width, pixels.height).dump(2) << "\n";
}

}  // namespace fovea::editor
