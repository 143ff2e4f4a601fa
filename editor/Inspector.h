// The inspector: runs a graph every frame in a window and shows the graph (GraphLayout), a
// preview of any field, per-pass GPU times and the selected pass's parameters (docs/inspector.md).
#pragma once
#include <array>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "editor/FreeFlyCamera.h"
#include "editor/GraphLayout.h"
#include "editor/GraphSession.h"
#include "editor/InspectorScript.h"
#include "editor/PreviewImage.h"
#include "editor/VulkanWindow.h"

struct ImDrawList;  // imgui.h, included by the .cpp files only
struct ImVec2;

namespace fovea::editor {

struct InspectorOptions {
    std::string graphFile;   // watched: a change on disk reloads it
    uint32_t frames = 0;     // 0 = until the window is closed
    std::string screenshot;  // after the last frame: PNG of the window + <file>.json
    std::vector<ScriptCommand> script;
    bool quiet = false;
    // --reference FILE: an image to compare the preview with ("reference" in `compare`).
    std::string referenceFile;
    image::ImageRGBA reference;
    // --overwrite: script screenshots and `saveas` may replace files (the UI asks instead).
    bool overwrite = false;
    // Scripted and screenshot runs ignore the real mouse: the pointer of a virtual display sits
    // somewhere over the window and would move the gaze and open tooltips at random.
    bool ignoreMouse = false;
};

// Node colour by status in the last frame (docs/inspector.md), RGB 0..255.
std::array<uint8_t, 3> statusColour(graph::PassStatus status);

// Per-frame CPU wall times in ms (docs/benchmarks.md, "Inspector overhead").
struct InspectorTimes {
    double graph = 0;    // session.runFrame: record + submit + wait for the graph's frame
    double preview = 0;  // read the previewed field(s) back + convert them
    double ui = 0;       // ImGui NewFrame .. Render
    double present = 0;  // record the UI, submit, present, wait
};

// A parameter change as applied (docs/inspector.md, "Parameters"; docs/benchmarks.md).
struct AppliedChange {
    std::string what;
    double ms = 0;  // CPU wall time of compile + update (or rebuild)
    graph::RenderGraph::UpdateResult result;
};

class Inspector {
public:
    Inspector(GraphSession& session, VulkanWindow& window, InspectorOptions options);
    ~Inspector();
    Inspector(const Inspector&) = delete;
    Inspector& operator=(const Inspector&) = delete;

    // Runs until the frame count is reached or the window is closed. Returns the number of
    // frames drawn.
    uint32_t run();
    const std::vector<InspectorTimes>& times() const { return mTimes; }
    const std::vector<AppliedChange>& changes() const { return mChanges; }
    // Bytes the preview holds: CPU copies of the shown images and the window's staging and
    // read-back buffers (docs/benchmarks.md, "Inspector overhead").
    uint64_t previewCpuBytes() const;

    // What the UI and the script do (public for the script and the panels).
    void selectPass(const std::string& pass);
    void previewField(const std::string& resource);  // "pass.field"; errors go to the window
    void setParam(const std::string& pass, const std::string& param, const nlohmann::json& value);
    void setParamText(const std::string& passParam, const std::string& text);
    // `paramsOnly`: a parameter edit (RenderGraph::update); else a full rebuild.
    void applyDesc(const graph::GraphDesc& desc, const std::string& what, bool paramsOnly);
    void reload(const std::string& path);
    // The second image: "pass.field", "reference" (--reference) or "" (none).
    void compareWith(const std::string& source);
    // Writes the graph with the edited parameters and the node positions (editor block).
    // Refuses an existing file unless `overwrite` (the UI asks first). Returns false on error.
    bool saveAs(const std::string& path, bool overwrite);
    // The previewed field (or, with the difference view on, |A - B|) at its own size: EXR in
    // full float, PNG as displayed.
    void savePreview(const std::string& path);
    void setFreeFly(bool on);

private:
    void runScript(uint32_t frame, std::vector<std::string>& screenshots,
                   std::vector<std::string>& previewShots);
    void runCommand(const ScriptCommand& cmd, std::vector<std::string>& screenshots,
                    std::vector<std::string>& previewShots);
    void pollGraphFile();
    void drawUi();
    void drawGraphView();
    // The graph view's parts: the edges (returns the field of the edge a click hit, or ""), one
    // node (returns true when its header was dragged), a node's input and output slots.
    std::string drawEdges(ImDrawList* draw, ImVec2 origin, bool clicked) const;
    bool drawNode(ImDrawList* draw, ImVec2 origin, size_t index);
    void drawNodeSlots(ImDrawList* draw, ImVec2 origin, const LayoutNode& node);
    void drawPreviewPanel();
    void drawSidePanel();
    void drawTimings();
    void updatePreview();
    void drawSaveAs();
    void handlePreviewMouse();
    void handleFreeFlyKeys();
    void drawPixelValues();
    void applyGazeFromMouse(const std::pair<uint32_t, uint32_t>& px);
    nlohmann::json screenshotInfo(uint32_t width, uint32_t height) const;
    void writeScreenshot(const std::string& path, const image::ImageRGBA& pixels) const;
    void relayout();
    void setError(const std::string& message);

    GraphSession& mSession;
    VulkanWindow& mWindow;
    InspectorOptions mOptions;
    GraphLayout mLayout;
    std::string mSelected;     // pass name
    std::string mPreview;      // "pass.field" (an output, or an input: the edge it reads)
    std::string mCompare;      // second image: "pass.field", "reference" or ""
    bool mDifference = false;  // right pane: |A - B| instead of B
    PreviewSettings mSettings;
    NodePositions mPositions;               // from the editor block and dragging
    std::optional<FreeFlyCamera> mFreeFly;  // set: the camera is steered, not the path's
    std::vector<AppliedChange> mChanges;
    std::string mSaveAsPath = "graph_edited.json";
    bool mConfirmOverwrite = false;
    std::optional<Gaze> mGaze;
    bool mPaused = false, mStep = false;
    std::string mError;
    std::optional<std::filesystem::file_time_type> mGraphTime;
    uint32_t mFrame = 0;
    graph::FrameTiming mLastTiming;
    std::deque<float> mFrameMsHistory;
    // The preview: the field's content (CPU copy), the bytes put under the UI and the placement.
    image::ImageRGBA mPreviewImage, mCompareImage, mDifferenceImage;
    bool mPreviewDisplayEncoded = false, mCompareDisplayEncoded = false;
    PreviewBlit mBlit;
    PreviewFit mFit, mFitB;  // left pane (A), right pane (B or |A - B|) when comparing
    float mPreviewRect[4] = {0, 0, 0, 0};  // x, y, w, h in window pixels (this frame's layout)
    std::vector<std::array<float, 4>> mNodeRects;  // per plan node: header x, y, w, h (window)
    std::array<float, 4> mCanvasClip{0, 0, 0, 0};  // visible part of the graph view (x0 y0 x1 y1)
    bool mGazeFollowsMouse = true;
    std::vector<InspectorTimes> mTimes;
};

}  // namespace fovea::editor
