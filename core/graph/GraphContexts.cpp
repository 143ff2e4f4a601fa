#include "core/graph/GraphContexts.h"

#include <filesystem>

#include "core/graph/RenderGraph.h"
#include "core/scene/SceneGpu.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Context.h"
#include "core/vk/Resources.h"

namespace fovea::graph {

gpu::Context& GraphCompileContext::gpu() {
    return mGraph.gpu();
}

ResourceExtent GraphCompileContext::extent(const std::string& field) const {
    size_t resource = kNone;
    if (auto own = mPlan.resourceOf.find({mNode, field}); own != mPlan.resourceOf.end())
        resource = own->second;
    else if (auto in = mPlan.inputs.find({mNode, field}); in != mPlan.inputs.end())
        resource = in->second.resource;
    if (resource == kNone) return {};
    const ResourcePlan& r = mPlan.resources[resource];
    return {r.width, r.height, r.format, r.bufferBytes};
}

bool GraphCompileContext::connected(const std::string& input) const {
    return mPlan.inputs.count({mNode, input}) > 0;
}

std::unique_ptr<gpu::ComputePipeline> GraphCompileContext::createPipeline(
    const std::string& shaderPath, const std::vector<std::pair<std::string, std::string>>& defines,
    const std::vector<std::string>& extraResources) {
    auto pipeline = mGraph.pipeline(shaderPath, defines);
    const PassNode& node = mPlan.nodes[mNode];
    std::vector<std::string> names = extraResources;
    for (const auto& f : node.reflection.fields()) {
        names.push_back(f.name);
        for (uint32_t back = 1; back <= f.historyFrames; ++back)
            names.push_back(previousBindingName(f.name, back));
    }
    // Binding by name: every resource the shader declares must be a field of the pass (or one
    // the pass binds itself). Catching it here turns a silent unbound descriptor into an error.
    for (const auto& b : pipeline->interface().bindings) {
        if (std::find(names.begin(), names.end(), b.name) != names.end()) continue;
        // scene_* resources are bound by SceneGpu::bind (docs/scene-gpu.md).
        if (mGraph.scene() && b.name.rfind("scene_", 0) == 0) continue;
        if (b.name == "camera_info") continue;  // bound by bindFields from the graph's camera
        std::string fields;
        for (const auto& f : node.reflection.fields())
            fields += (fields.empty() ? "" : ", ") + f.name;
        throw RuntimeError("pass '" + node.name + "' (" + node.type + "): shader '" + shaderPath +
                           "' expects resource '" + b.name + "' but the pass has no such field" +
                           didYouMean(b.name, names) + " (fields: " + fields + ")");
    }
    return pipeline;
}

const scene::SceneGpu* GraphCompileContext::scene() const {
    return mGraph.scene();
}

std::string GraphCompileContext::resolvePath(const std::string& path) const {
    const std::filesystem::path value(path);
    if (path.empty() || value.is_absolute()) return path;
    // A label of a graph not read from a file ("(editor)") has no folder: relative to the cwd.
    return (std::filesystem::path(mPlan.file).parent_path() / value).lexically_normal().string();
}

gpu::Context& GraphExecuteContext::gpu() {
    return mGraph.gpu();
}
const scene::SceneGpu* GraphExecuteContext::scene() const {
    return mGraph.scene();
}
const scene::FrameCamera& GraphExecuteContext::camera() const {
    return mGraph.camera();
}

bool GraphExecuteContext::connected(const std::string& input) const {
    return mPlan.inputs.count({mNode, input}) > 0;
}

const gpu::Image& GraphExecuteContext::image(const std::string& field) {
    return mGraph.imageFor(mNode, field);
}

const gpu::Buffer& GraphExecuteContext::buffer(const std::string& field) {
    return mGraph.bufferFor(mNode, field);
}

bool GraphExecuteContext::historyValid(const std::string& field, uint32_t framesBack) const {
    return mGraph.historyValidFor(mNode, field, framesBack);
}

const gpu::Image& GraphExecuteContext::previous(const std::string& field, uint32_t framesBack) {
    return mGraph.previousFor(mNode, field, framesBack);
}

std::optional<uint64_t> GraphExecuteContext::inputVersion(const std::string& input) const {
    return mGraph.inputVersionFor(mNode, input);
}

void GraphExecuteContext::dispatch(gpu::ComputePipeline& pipeline, uint32_t threadsX,
                                   uint32_t threadsY, uint32_t threadsZ) {
    mHazards.beforeDispatch(mCmd, pipeline);
    mGraph.beginDispatchTiming(mCmd, mNode, pipeline.shaderPath());
    pipeline.dispatch(mCmd, threadsX, threadsY, threadsZ);
    mGraph.endDispatchTiming(mCmd);
}

void GraphExecuteContext::dispatchIndirect(gpu::ComputePipeline& pipeline, const gpu::Buffer& args,
                                           vk::DeviceSize offset) {
    mHazards.beforeDispatch(mCmd, pipeline, args.buffer());
    mGraph.beginDispatchTiming(mCmd, mNode, pipeline.shaderPath());
    pipeline.dispatchIndirect(mCmd, args, offset);
    mGraph.endDispatchTiming(mCmd);
}

void GraphExecuteContext::bindFields(gpu::ComputePipeline& pipeline) {
    const PassNode& node = mPlan.nodes[mNode];
    if (pipeline.hasBinding("camera_info")) pipeline.bind("camera_info", mGraph.cameraBuffer());
    if (mGraph.scene()) mGraph.scene()->bind(pipeline);
    for (const auto& b : pipeline.interface().bindings) {
        const FieldDesc* f = node.reflection.find(b.name);
        if (!f) {
            // prev_<field> / prev<N>_<field>: a previous frame of a field with declared history.
            if (auto [field, back] = parsePreviousBindingName(b.name); back > 0) {
                const FieldDesc* h = node.reflection.find(field);
                if (h && back <= h->historyFrames) pipeline.bind(b.name, previous(field, back));
            }
            continue;  // otherwise bound by the pass itself (checked at compile)
        }
        bindResource(pipeline, b, *f);
    }
}

void GraphExecuteContext::bindField(gpu::ComputePipeline& pipeline, const std::string& binding,
                                    const std::string& field) {
    const FieldDesc* f = mPlan.nodes[mNode].reflection.find(field);
    if (!f)
        throw RuntimeError("pass '" + mPlan.nodes[mNode].name + "' binds unknown field '" + field +
                           "'");
    for (const auto& b : pipeline.interface().bindings)
        if (b.name == binding) return bindResource(pipeline, b, *f);
}

void GraphExecuteContext::bindResource(gpu::ComputePipeline& pipeline, const gpu::ShaderBinding& b,
                                       const FieldDesc& f) {
    bool isBuffer = b.kind == gpu::DescriptorKind::StorageBuffer ||
                    b.kind == gpu::DescriptorKind::UniformBuffer;
    if (f.kind == FieldKind::Input && !connected(f.name)) {
        // Optional input left open: bind a 1x1 zero image (or a small zeroed buffer) so the
        // shader's descriptor is valid; the pass decides from connected() whether to read it.
        if (isBuffer)
            pipeline.bind(b.name, mGraph.dummyBuffer());
        else
            pipeline.bind(b.name, mGraph.dummyImage(b.imageFormat));
        return;
    }
    if (isBuffer)
        pipeline.bind(b.name, buffer(f.name));
    else
        pipeline.bind(b.name, image(f.name));
}

}  // namespace fovea::graph
