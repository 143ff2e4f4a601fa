#include "editor/Inspector.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <chrono>
#include <fstream>
#include <iostream>

#include "core/graph/CompilerStages.h"
#include "core/graph/PassRegistry.h"
#include "core/util/Error.h"
#include "core/vk/Context.h"
#include "core/vk/Formats.h"
#include "core/vk/Resources.h"

namespace fovea::editor {

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// The backend reports Vulkan errors through this hook; they are rare (out of memory) and the
// next vulkan-hpp call would throw anyway, so they are printed, not ignored.
void checkImGuiVk(VkResult result) {
    if (result < 0) std::cerr << "fovea: inspect: ImGui Vulkan backend error " << result << "\n";
}

}  // namespace

Inspector::Inspector(GraphSession& session, VulkanWindow& window, InspectorOptions options)
    : mSession(session), mWindow(window), mOptions(std::move(options)) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // the layout is fixed: screenshots are reproducible
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForVulkan(window.handle(), true);
    gpu::Context& ctx = session.gpu();
    ImGui_ImplVulkan_InitInfo info{};
    info.Instance = *ctx.instance();
    info.PhysicalDevice = *ctx.physicalDevice();
    info.Device = *ctx.device();
    info.QueueFamily = ctx.queueFamily();
    info.Queue = *ctx.queue();
    info.DescriptorPool = window.descriptorPool();
    info.MinImageCount = window.minImageCount();
    info.ImageCount = std::max(window.imageCount(), window.minImageCount());
    info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    info.CheckVkResultFn = &checkImGuiVk;
    ImGui_ImplVulkan_Init(&info, window.renderPass());
    window.submitOnce([](vk::CommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();

    if (!mOptions.graphFile.empty() && std::filesystem::exists(mOptions.graphFile))
        mGraphTime = std::filesystem::last_write_time(mOptions.graphFile);
    relayout();
    // Start on the first marked output and the pass producing it.
    for (const auto& out : session.desc().outputs) {
        previewField(out.source.str());
        if (!mPreview.empty()) break;
    }
    mError.clear();
    if (!mPreview.empty()) mSelected = mPreview.substr(0, mPreview.find('.'));
}

Inspector::~Inspector() {
    try {
        mSession.gpu().device().waitIdle();
    } catch (const vk::SystemError&) {
        // device lost: nothing to wait for
    }
    ImGui_ImplVulkan_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void Inspector::relayout() {
    mLayout = layoutGraph(mSession.graph().plan());
}

void Inspector::setError(const std::string& message) {
    mError = message;
    if (!mOptions.quiet) std::cerr << "fovea: inspect: " << message << "\n";
}

void Inspector::selectPass(const std::string& pass) {
    if (mSession.graph().plan().findNode(pass) == graph::kNone)
        return setError("select: no pass '" + pass + "' in the graph");
    mSelected = pass;
}

void Inspector::previewField(const std::string& resource) {
    const auto& plan = mSession.graph().plan();
    auto endpoint = graph::parseEndpoint(resource);
    const size_t node = endpoint ? plan.findNode(endpoint->pass) : graph::kNone;
    if (node == graph::kNone) return setError("preview: no pass for '" + resource + "'");
    if (!plan.nodes[node].alive)
        return setError("preview: pass '" + endpoint->pass + "' is culled (" +
                        plan.nodes[node].cullReason + ")");
    auto it = plan.resourceOf.find({node, endpoint->field});
    if (it == plan.resourceOf.end() || !plan.resources[it->second].isImage)
        return setError("preview: '" + resource + "' is not an image output of its pass");
    mPreview = resource;
}

void Inspector::setParam(const std::string& pass, const std::string& param,
                         const nlohmann::json& value) {
    graph::GraphDesc next = mSession.desc();
    for (auto& p : next.passes)
        if (p.name == pass) {
            p.params[param] = value;
            return applyDesc(next, "set " + pass + "." + param);
        }
    setError("set: no pass '" + pass + "' in the graph");
}

void Inspector::setParamText(const std::string& passParam, const std::string& text) {
    const size_t dot = passParam.find('.');
    const auto& plan = mSession.graph().plan();
    const size_t node =
        dot == std::string::npos ? graph::kNone : plan.findNode(passParam.substr(0, dot));
    if (node == graph::kNone) return setError("set: expected PASS.PARAM, got '" + passParam + "'");
    try {
        const std::string param = passParam.substr(dot + 1);
        setParam(passParam.substr(0, dot), param,
                 graph::parseParamText(*plan.nodes[node].pass, param, text, "set"));
    } catch (const InputError& e) {
        setError(e.what());
    }
}

// A change is checked on the CPU first (every compile stage, errors with the JSON pointer), then
// built; a failure keeps the last good graph running and shows the error.
void Inspector::applyDesc(const graph::GraphDesc& desc, const std::string& what) {
    try {
        graph::compileGraphPlan(desc, graph::passRegistry(), mSession.compileOptions());
        mSession.rebuild(desc);
        mError.clear();
    } catch (const std::exception& e) {
        setError(what + ": " + e.what() + " (the last good graph keeps running)");
    }
    relayout();
    if (!mPreview.empty()) {
        const std::string keep = mPreview;
        mPreview.clear();
        const std::string error = mError;
        previewField(keep);
        if (mPreview.empty()) mError = error.empty() ? mError : error + "\n" + mError;
    }
}

void Inspector::reload(const std::string& path) {
    try {
        applyDesc(mSession.loadGraphFile(path), "reload " + path);
    } catch (const std::exception& e) {
        setError("reload " + path + ": " + e.what() + " (the last good graph keeps running)");
    }
}

void Inspector::pollGraphFile() {
    if (!mGraphTime) return;
    std::error_code ec;
    const auto time = std::filesystem::last_write_time(mOptions.graphFile, ec);
    if (ec || time == *mGraphTime) return;
    mGraphTime = time;
    reload(mOptions.graphFile);
}

void Inspector::runCommand(const ScriptCommand& cmd, std::vector<std::string>& screenshots) {
    const auto& a = cmd.args;
    auto number = [&](const std::string& text) {
        try {
            size_t used = 0;
            const float v = std::stof(text, &used);
            if (used == text.size()) return v;
        } catch (const std::exception&) {
        }
        throw InputError(cmd.where, "", "expected a number, got '" + text + "'");
    };
    if (cmd.verb == "select") {
        selectPass(a[0]);
    } else if (cmd.verb == "set") {
        setParamText(a[0], a[1]);
    } else if (cmd.verb == "preview") {
        previewField(a[0]);
    } else if (cmd.verb == "channel") {
        auto c = parsePreviewChannel(a[0]);
        if (!c) throw InputError(cmd.where, "", "channel: expected rgb, r, g, b, a or luminance");
        mSettings.channel = *c;
    } else if (cmd.verb == "exposure") {
        mSettings.exposure = number(a[0]);
    } else if (cmd.verb == "falsecolour") {
        if (a[0] != "on" && a[0] != "off") throw InputError(cmd.where, "", "expected on or off");
        mSettings.falseColour = a[0] == "on";
    } else if (cmd.verb == "gaze") {
        const glm::vec2 g(number(a[0]), number(a[1]));
        if (g.x < 0 || g.x > 1 || g.y < 0 || g.y > 1)
            throw InputError(cmd.where, "", "gaze: expected coordinates in [0,1]");
        Gaze gaze{g, g};
        if (mSession.stereo()) {  // the eye under the point gets it, in its own coordinates
            gaze = mGaze.value_or(Gaze{glm::vec2(0.5f), glm::vec2(0.5f)});
            const int eye = g.x < 0.5f ? 0 : 1;
            gaze[size_t(eye)] = glm::vec2(g.x * 2.0f - float(eye), g.y);
        }
        mGaze = gaze;
    } else if (cmd.verb == "pause") {
        mPaused = true;
    } else if (cmd.verb == "resume") {
        mPaused = false;
    } else if (cmd.verb == "step") {
        mStep = true;
    } else if (cmd.verb == "reset") {
        mSession.graph().reset();
    } else if (cmd.verb == "reload") {
        reload(a[0]);
    } else if (cmd.verb == "screenshot") {
        screenshots.push_back(a[0]);
    }
}

void Inspector::runScript(uint32_t frame, std::vector<std::string>& screenshots) {
    for (const auto& cmd : mOptions.script)
        if (cmd.frame == frame) runCommand(cmd, screenshots);
}

void Inspector::updatePreview() {
    if (mPreview.empty()) return;
    try {
        const gpu::Image& img = mSession.graph().image(mPreview);
        mPreviewImage = {img.width(), img.height(), img.downloadRGBA32F(mSession.gpu())};
        mPreviewDisplayEncoded = gpu::formatIsUnorm8(img.format());
    } catch (const std::exception& e) {
        setError("preview " + mPreview + ": " + e.what());
        mPreview.clear();
    }
}

uint32_t Inspector::run() {
    const uint32_t limit = mOptions.frames;
    for (mFrame = 0; (limit == 0 || mFrame < limit) && !mWindow.shouldClose(); ++mFrame) {
        glfwPollEvents();
        std::vector<std::string> screenshots;
        runScript(mFrame, screenshots);
        if (mFrame + 1 == limit && !mOptions.screenshot.empty())
            screenshots.push_back(mOptions.screenshot);
        pollGraphFile();
        InspectorTimes t;
        auto start = Clock::now();
        if (!mPaused || mStep) {
            try {
                mLastTiming = mSession.runFrame(mGaze);
                mFrameMsHistory.push_back(float(mLastTiming.gpuMs));
                if (mFrameMsHistory.size() > 120) mFrameMsHistory.pop_front();
            } catch (const RuntimeError& e) {
                setError(std::string("frame: ") + e.what());
                mPaused = true;
            }
            mStep = false;
        }
        t.graph = msSince(start);
        start = Clock::now();
        updatePreview();
        t.preview = msSince(start);
        start = Clock::now();
        ImGui_ImplVulkan_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        if (mOptions.ignoreMouse) {
            ImGuiIO& io = ImGui::GetIO();
            io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
            for (bool& down : io.MouseDown) down = false;
        }
        ImGui::NewFrame();
        drawUi();
        ImGui::Render();
        t.ui = msSince(start);
        start = Clock::now();
        // The preview bytes fill this frame's rectangle (known only after the UI was laid out).
        const bool showPreview = !mPreview.empty() && mPreviewRect[2] >= 1 && mPreviewRect[3] >= 1;
        if (showPreview) {
            const vk::Extent2D extent = mWindow.extent();
            const int x = std::clamp(int(mPreviewRect[0]), 0, int(extent.width) - 1);
            const int y = std::clamp(int(mPreviewRect[1]), 0, int(extent.height) - 1);
            const uint32_t w = std::min(uint32_t(mPreviewRect[2]), extent.width - uint32_t(x));
            const uint32_t h = std::min(uint32_t(mPreviewRect[3]), extent.height - uint32_t(y));
            PreviewSettings settings = mSettings;
            settings.displayEncoded = mPreviewDisplayEncoded;
            mBlit = makePreview(mPreviewImage, x, y, w, h, settings, mWindow.bgra(), &mFit);
        }
        image::ImageRGBA shot;
        ImDrawData* draw = ImGui::GetDrawData();
        // A frame is dropped only when the swapchain was out of date (recreated meanwhile).
        for (int attempt = 0; attempt < 3; ++attempt)
            if (mWindow.drawFrame(
                    [&](vk::CommandBuffer cmd) { ImGui_ImplVulkan_RenderDrawData(draw, cmd); },
                    showPreview ? &mBlit : nullptr, screenshots.empty() ? nullptr : &shot))
                break;
        t.present = msSince(start);
        for (const auto& path : screenshots)
            if (shot.width > 0) writeScreenshot(path, shot);
        mTimes.push_back(t);
    }
    return mFrame;
}

}  // namespace fovea::editor
