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
    std::string problems;
    mPositions = readNodePositions(session.desc().editor, problems);
    relayout();
    // Start on the first marked output and the pass producing it.
    for (const auto& out : session.desc().outputs) {
        previewField(out.source.str());
        if (!mPreview.empty()) break;
    }
    mError.clear();
    if (!problems.empty()) setError(mOptions.graphFile + ": " + problems);
    if (!mPreview.empty()) mSelected = mPreview.substr(0, mPreview.find('.'));
    if (!mOptions.referenceFile.empty()) mCompare = "reference";
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
    mLayout = layoutGraph(mSession.graph().plan(), {}, &mPositions);
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

namespace {

// An image field "pass.field" of a live pass: an output or internal, or a connected input (the
// edge it reads). Empty when it is one, else why not.
std::string checkPreviewable(const graph::CompiledPlan& plan, const std::string& resource) {
    auto endpoint = graph::parseEndpoint(resource);
    const size_t node = endpoint ? plan.findNode(endpoint->pass) : graph::kNone;
    if (node == graph::kNone) return "no pass for '" + resource + "'";
    if (!plan.nodes[node].alive)
        return "pass '" + endpoint->pass + "' is culled (" + plan.nodes[node].cullReason + ")";
    if (auto it = plan.resourceOf.find({node, endpoint->field}); it != plan.resourceOf.end())
        return plan.resources[it->second].isImage ? "" : "'" + resource + "' is a buffer";
    if (auto in = plan.inputs.find({node, endpoint->field}); in != plan.inputs.end())
        return in->second.resource != graph::kNone && plan.resources[in->second.resource].isImage
                   ? ""
                   : "'" + resource + "' is a buffer input";
    return "'" + resource + "' is not an image field (output or connected input) of its pass";
}

}  // namespace

void Inspector::previewField(const std::string& resource) {
    const std::string problem = checkPreviewable(mSession.graph().plan(), resource);
    if (!problem.empty()) return setError("preview: " + problem);
    mPreview = resource;
}

void Inspector::compareWith(const std::string& source) {
    if (source.empty() || source == "off") {
        mCompare.clear();
        mCompareImage = {};
        return;
    }
    if (source == "reference") {
        if (mOptions.reference.width == 0)
            return setError("compare: no reference image (start with --reference FILE)");
        mCompare = source;
        return;
    }
    const std::string problem = checkPreviewable(mSession.graph().plan(), source);
    if (!problem.empty()) return setError("compare: " + problem);
    mCompare = source;
}

void Inspector::setParam(const std::string& pass, const std::string& param,
                         const nlohmann::json& value) {
    graph::GraphDesc next = mSession.desc();
    for (auto& p : next.passes)
        if (p.name == pass) {
            p.params[param] = value;
            return applyDesc(next, "set " + pass + "." + param, true);
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
// applied: a parameter edit through RenderGraph::update (only what changed recompiles), anything
// else rebuilt; a failure keeps the last good graph running and shows the error.
void Inspector::applyDesc(const graph::GraphDesc& desc, const std::string& what, bool paramsOnly) {
    try {
        graph::compileGraphPlan(desc, graph::passRegistry(), mSession.compileOptions());
        AppliedChange change{what, 0, {}};
        const auto start = Clock::now();
        if (paramsOnly)
            change.result = mSession.update(desc);
        else
            mSession.rebuild(desc);
        change.ms = msSince(start);
        mChanges.push_back(change);
        if (!mOptions.quiet) {
            std::cerr << "fovea: inspect: " << what << ": " << change.ms << " ms, ";
            if (!paramsOnly) {
                std::cerr << "full rebuild\n";
            } else {
                std::cerr << (change.result.inPlace ? "in place (recompiled:"
                                                    : "rebuilt (plan changed;");
                for (const auto& p : change.result.recompiled) std::cerr << " " << p;
                std::cerr << "; pipelines created " << change.result.pipelinesCreated << ", reused "
                          << change.result.pipelinesReused << ")\n";
            }
        }
        mError.clear();
    } catch (const std::exception& e) {
        setError(what + ": " + e.what() + " (the last good graph keeps running)");
    }
    relayout();
    const std::string error = mError;
    for (std::string* field : {&mPreview, &mCompare}) {
        if (field->empty() || *field == "reference") continue;
        const std::string keep = *field;
        field->clear();
        if (field == &mPreview)
            previewField(keep);
        else
            compareWith(keep);
    }
    if (!error.empty() && mError != error) mError = error + "\n" + mError;
}

void Inspector::reload(const std::string& path) {
    try {
        graph::GraphDesc desc = mSession.loadGraphFile(path);
        applyDesc(desc, "reload " + path, false);
        if (mSession.desc() == desc) {  // loaded: its editor block places the nodes
            std::string problems;
            mPositions = readNodePositions(desc.editor, problems);
            relayout();
            if (!problems.empty()) setError(path + ": " + problems);
        }
    } catch (const std::exception& e) {
        setError("reload " + path + ": " + e.what() + " (the last good graph keeps running)");
    }
}

bool Inspector::saveAs(const std::string& path, bool overwrite) {
    graph::GraphDesc desc = mSession.desc();
    desc.editor = writeNodePositions(desc.editor, mLayout);
    try {
        graph::saveGraphFile(desc, path, overwrite);
    } catch (const std::exception& e) {
        setError(std::string("save as: ") + e.what());
        return false;
    }
    if (!mOptions.quiet) std::cerr << "fovea: inspect: saved " << path << "\n";
    return true;
}

void Inspector::savePreview(const std::string& path) {
    const image::ImageRGBA& shown =
        mDifference && !mDifferenceImage.pixels.empty() ? mDifferenceImage : mPreviewImage;
    if (shown.width == 0) return setError("previewshot " + path + ": nothing previewed");
    try {
        const std::string ext = std::filesystem::path(path).extension().string();
        if (ext == ".exr") {
            image::writeExr(path, shown);
        } else {
            PreviewSettings settings = mSettings;
            settings.displayEncoded = mPreviewDisplayEncoded && &shown == &mPreviewImage;
            image::writePng(path, displayImage(shown, settings), image::PngEncoding::AsIs);
        }
    } catch (const std::exception& e) {
        setError("previewshot " + path + ": " + e.what());
    }
}

void Inspector::setFreeFly(bool on) {
    if (on && !mFreeFly) {
        if (!mSession.hasScene()) return setError("free-fly: the graph runs without a scene");
        mFreeFly.emplace(mSession.pathCamera());
    } else if (!on) {
        mFreeFly.reset();
    }
}

uint64_t Inspector::previewCpuBytes() const {
    uint64_t bytes = 0;
    for (const auto* img : {&mPreviewImage, &mCompareImage, &mDifferenceImage, &mOptions.reference})
        bytes += img->pixels.size() * sizeof(float);
    return bytes + mBlit.bytes.size();
}

void Inspector::pollGraphFile() {
    if (!mGraphTime) return;
    std::error_code ec;
    const auto time = std::filesystem::last_write_time(mOptions.graphFile, ec);
    if (ec || time == *mGraphTime) return;
    mGraphTime = time;
    reload(mOptions.graphFile);
}

void Inspector::runCommand(const ScriptCommand& cmd, std::vector<std::string>& screenshots,
                           std::vector<std::string>& previewShots) {
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
    } else if (cmd.verb == "rebuild") {
        applyDesc(mSession.desc(), "rebuild", false);
    } else if (cmd.verb == "screenshot") {
        screenshots.push_back(a[0]);
    } else if (cmd.verb == "compare") {
        compareWith(a[0]);
    } else if (cmd.verb == "difference") {
        if (a[0] != "on" && a[0] != "off") throw InputError(cmd.where, "", "expected on or off");
        mDifference = a[0] == "on";
    } else if (cmd.verb == "zoom") {
        const float zoom = number(a[0]), u = number(a[1]), v = number(a[2]);
        if (zoom < kMinZoom || zoom > kMaxZoom || u < 0 || u > 1 || v < 0 || v > 1)
            throw InputError(cmd.where, "", "zoom: expected FACTOR in [1,64] and U V in [0,1]");
        mSettings.view = {zoom, u, v};
    } else if (cmd.verb == "camera") {
        if (a[0] != "path" && a[0] != "freefly")
            throw InputError(cmd.where, "", "camera: expected path or freefly");
        setFreeFly(a[0] == "freefly");
    } else if (cmd.verb == "move") {
        setFreeFly(true);
        if (mFreeFly) mFreeFly->move({number(a[0]), number(a[1]), number(a[2])});
    } else if (cmd.verb == "look") {
        setFreeFly(true);
        if (mFreeFly) mFreeFly->look(number(a[0]), number(a[1]));
    } else if (cmd.verb == "place") {
        if (mSession.graph().plan().findNode(a[0]) == graph::kNone)
            return setError("place: no pass '" + a[0] + "' in the graph");
        mPositions[a[0]] = {number(a[1]), number(a[2])};
        relayout();
    } else if (cmd.verb == "saveas") {
        saveAs(a[0], mOptions.overwrite);
    } else if (cmd.verb == "previewshot") {
        previewShots.push_back(a[0]);
    }
}

void Inspector::runScript(uint32_t frame, std::vector<std::string>& screenshots,
                          std::vector<std::string>& previewShots) {
    for (const auto& cmd : mOptions.script)
        if (cmd.frame == frame) runCommand(cmd, screenshots, previewShots);
}

void Inspector::updatePreview() {
    auto readBack = [&](std::string& source, image::ImageRGBA& out, bool& encoded) {
        if (source.empty()) return;
        try {
            const gpu::Image& img = mSession.graph().image(source);
            out = {img.width(), img.height(), img.downloadRGBA32F(mSession.gpu())};
            encoded = gpu::formatIsUnorm8(img.format());
        } catch (const std::exception& e) {
            setError("preview " + source + ": " + e.what());
            source.clear();
            out = {};
        }
    };
    readBack(mPreview, mPreviewImage, mPreviewDisplayEncoded);
    if (mCompare == "reference") {
        mCompareImage = mOptions.reference;
        mCompareDisplayEncoded = false;
    } else {
        readBack(mCompare, mCompareImage, mCompareDisplayEncoded);
    }
    mDifferenceImage = {};
    if (mDifference && !mCompare.empty())
        mDifferenceImage = differenceImage(mPreviewImage, mCompareImage);
}

void Inspector::handleFreeFlyKeys() {
    if (!mFreeFly || mOptions.ignoreMouse || ImGui::GetIO().WantCaptureKeyboard) return;
    // ImGui 1.86 has no named keys (ImGuiKey_W came in 1.87): ask GLFW directly.
    GLFWwindow* w = mWindow.handle();
    auto down = [&](int key) { return glfwGetKey(w, key) == GLFW_PRESS ? 1.0f : 0.0f; };
    const glm::vec3 local(down(GLFW_KEY_D) - down(GLFW_KEY_A), down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                          down(GLFW_KEY_W) - down(GLFW_KEY_S));
    const float fast = down(GLFW_KEY_LEFT_SHIFT) > 0 ? 4.0f : 1.0f;
    if (local != glm::vec3(0.0f)) mFreeFly->move(local * mFreeFly->step() * fast);
}

uint32_t Inspector::run() {
    const uint32_t limit = mOptions.frames;
    for (mFrame = 0; (limit == 0 || mFrame < limit) && !mWindow.shouldClose(); ++mFrame) {
        glfwPollEvents();
        std::vector<std::string> screenshots, previewShots;
        runScript(mFrame, screenshots, previewShots);
        if (mFrame + 1 == limit && !mOptions.screenshot.empty())
            screenshots.push_back(mOptions.screenshot);
        pollGraphFile();
        handleFreeFlyKeys();
        InspectorTimes t;
        auto start = Clock::now();
        if (!mPaused || mStep) {
            try {
                FrameRequest request{mGaze, std::nullopt};
                if (mFreeFly) request.camera = mFreeFly->pose();
                mLastTiming = mSession.runFrame(request);
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
        for (const auto& path : previewShots) savePreview(path);
        t.preview = msSince(start);
        start = Clock::now();
        ImGui_ImplVulkan_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        if (mOptions.ignoreMouse) {
            ImGuiIO& io = ImGui::GetIO();
            io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
            for (bool& down : io.MouseDown) down = false;
            io.MouseWheel = 0;
        }
        ImGui::NewFrame();
        drawUi();
        ImGui::Render();
        t.ui = msSince(start);
        start = Clock::now();
        // The preview bytes fill this frame's rectangle (known only after the UI was laid out):
        // one pane, or two (A | B or A | |A - B|) when comparing.
        const bool showPreview = !mPreview.empty() && mPreviewRect[2] >= 1 && mPreviewRect[3] >= 1;
        if (showPreview) {
            const vk::Extent2D extent = mWindow.extent();
            const int x = std::clamp(int(mPreviewRect[0]), 0, int(extent.width) - 1);
            const int y = std::clamp(int(mPreviewRect[1]), 0, int(extent.height) - 1);
            const uint32_t w = std::min(uint32_t(mPreviewRect[2]), extent.width - uint32_t(x));
            const uint32_t h = std::min(uint32_t(mPreviewRect[3]), extent.height - uint32_t(y));
            PreviewSettings settings = mSettings;
            settings.displayEncoded = mPreviewDisplayEncoded;
            const bool two = !mCompare.empty() && mCompareImage.width > 0 && w >= 8;
            mBlit = {x, y, w, h, std::vector<uint8_t>(size_t(w) * h * 4, 0)};
            constexpr uint32_t kGap = 4;
            const uint32_t left = two ? (w - kGap) / 2 : w;
            drawPreviewPane(mPreviewImage, settings, mWindow.bgra(), mBlit, 0, left, &mFit);
            mFitB = {};
            if (two) {
                const bool diff = mDifference && mDifferenceImage.width > 0;
                PreviewSettings right = mSettings;
                right.displayEncoded = !diff && mCompareDisplayEncoded;
                drawPreviewPane(diff ? mDifferenceImage : mCompareImage, right, mWindow.bgra(),
                                mBlit, int(left + kGap), w - left - kGap, &mFitB);
            }
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
