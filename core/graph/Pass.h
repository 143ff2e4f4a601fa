// The pass contract. Every technique in fovea is a Pass: it declares parameters (params),
// resources (reflect), what it needs from the scene (sceneNeeds), builds pipelines once sizes and
// formats are final (compile), records commands (execute), and says when it may be skipped
// (isActive + bypass, cacheable). Barriers (between passes and between one pass's dispatches),
// allocation and history are the graph's job.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include <vulkan/vulkan_raii.hpp>

#include "core/graph/Param.h"
#include "core/graph/PassFacts.h"
#include "core/graph/Reflection.h"
#include "core/scene/SceneFeatures.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Resources.h"

namespace fovea::gpu {
class Context;
class Image;
class Buffer;
class ComputePipeline;
}  // namespace fovea::gpu

namespace fovea::scene {
class SceneGpu;
struct FrameCamera;
}  // namespace fovea::scene

namespace fovea::graph {

// Scene features a pass can require (core/scene/SceneFeatures.h). A pass whose needs the loaded
// scene does not meet is culled (with a reason) instead of running on missing data.
using scene::kSceneAlpha;
using scene::kSceneEmissive;
using scene::kSceneEnvironment;
using scene::kSceneEquirect;
using scene::kSceneGeometry;
using scene::kScenePunctual;
using scene::kSceneStereo;
using scene::kSceneTextures;
using scene::SceneFeature;
using scene::sceneFeatureNames;

struct FrameInfo {
    uint64_t index = 0;             // frames since the run started
    uint64_t framesSinceReset = 0;  // 0 on the first frame and after reset/resize/camera cut
    uint64_t seed = 0;
    uint32_t width = 0, height = 0;  // render size
    bool cameraCut = false;          // this frame starts a new shot (history was dropped)
};

struct ResourceExtent {
    uint32_t width = 0, height = 0;
    vk::Format format = vk::Format::eUndefined;
    uint64_t bytes = 0;  // buffers
};

// Handed to Pass::compile once sizes, formats and the scene are final.
class CompileContext {
public:
    virtual ~CompileContext() = default;
    virtual gpu::Context& gpu() = 0;
    virtual const FrameInfo& renderSize() const = 0;  // width/height of the graph
    // Size/format of a field as resolved by the graph (inputs: of the connected source).
    virtual ResourceExtent extent(const std::string& field) const = 0;
    virtual bool connected(const std::string& input) const = 0;
    // Creates a pipeline and checks that every resource the shader declares is a field of this
    // pass or listed in `extraResources` (resources the pass binds itself, e.g. a scene buffer).
    // A shader expecting `normal` in a pass that has none is a clear error here, not at dispatch.
    // The scene on the GPU, or null when the run has none (then no pass needing geometry is
    // alive). Its defines() specialize shaders for the scene's features.
    virtual const scene::SceneGpu* scene() const = 0;
    // A path parameter's value (ParamSpec::path) as a file to open: a relative path is resolved
    // against the graph file's folder, like defaults.camera, so a graph works from any working
    // directory. Absolute paths, and graphs not read from a file, are returned unchanged.
    virtual std::string resolvePath(const std::string& path) const = 0;
    virtual std::unique_ptr<gpu::ComputePipeline> createPipeline(
        const std::string& shaderPath,
        const std::vector<std::pair<std::string, std::string>>& defines = {},
        const std::vector<std::string>& extraResources = {}) = 0;
};

// Handed to Pass::execute each frame.
class ExecuteContext {
public:
    virtual ~ExecuteContext() = default;
    virtual gpu::Context& gpu() = 0;
    virtual const vk::raii::CommandBuffer& cmd() = 0;
    virtual const FrameInfo& frame() const = 0;
    virtual bool connected(const std::string& input) const = 0;
    // The image behind a field (input: the connected source's current or delayed image).
    virtual const gpu::Image& image(const std::string& field) = 0;
    virtual const gpu::Buffer& buffer(const std::string& field) = 0;
    // An input: false for a delayed input whose history does not exist yet (first frames,
    // reset, resize, camera cut); true for any other connected input.
    // An output/internal with declared history (FieldBuilder::history): true when previous(field,
    // framesBack) holds a frame written since the last reset, cut or resize (a rebuild that keeps
    // the field's name, size, format and ring, e.g. a parameter change, keeps it valid).
    virtual bool historyValid(const std::string& field, uint32_t framesBack = 1) const = 0;
    // The image of an output/internal with declared history as written `framesBack` frames ago
    // (1..historyFrames). Its content is undefined while historyValid() is false. Shaders get it
    // from bindFields as `prev_<field>` (framesBack 1) or `prev<N>_<field>`.
    virtual const gpu::Image& previous(const std::string& field, uint32_t framesBack = 1) = 0;
    // A number that changes whenever the source of the connected `input` writes it (a cached
    // source that did not run leaves it unchanged), so a pass can keep data derived from an input
    // across frames and rebuild it only when the input changed. nullopt = unknown (treat the
    // input as changed): a delayed input, an unconnected one, or a context without versions.
    virtual std::optional<uint64_t> inputVersion(const std::string&) const { return std::nullopt; }
    // Binds every shader resource whose name is a connected field of this pass, plus the scene
    // buffers (scene_*) and the frame camera (camera_info) when the shader declares them.
    virtual void bindFields(gpu::ComputePipeline& pipeline) = 0;
    // Binds field `field` to the shader resource `binding`, for a resource whose name cannot be
    // the field's (e.g. the GLSL keyword `layout`). An open optional input gets the zero dummy,
    // as in bindFields.
    virtual void bindField(gpu::ComputePipeline& pipeline, const std::string& binding,
                           const std::string& field) = 0;
    // The scene (null without one) and this frame's camera (a default one without a scene).
    virtual const scene::SceneGpu* scene() const = 0;
    virtual const scene::FrameCamera& camera() const = 0;
    // Records `pipeline`'s dispatch over threadsX x threadsY x threadsZ threads (its staged
    // bindings and push constants), preceded by the barrier those bindings need against this
    // pass's earlier dispatches in this frame (gpu::DispatchHazards: read or write after write,
    // write after read, indirect arguments). A pass dispatches through here and records no
    // barrier itself: the graph orders passes, the context orders a pass's dispatches.
    virtual void dispatch(gpu::ComputePipeline& pipeline, uint32_t threadsX, uint32_t threadsY = 1,
                          uint32_t threadsZ = 1) = 0;
    // The same with the group counts read from `args` at `offset` (ComputePipeline::
    // dispatchIndirect); a dispatch that wrote `args` earlier in the pass is waited for.
    virtual void dispatchIndirect(gpu::ComputePipeline& pipeline, const gpu::Buffer& args,
                                  vk::DeviceSize offset = 0) = 0;
};

// What Pass::statistics may read: the device and the pass's own buffer fields.
struct StatisticsContext {
    gpu::Context& gpu;
    std::function<const gpu::Buffer&(const std::string& field)> buffer;
};

// Handed to Pass::validate during compile (CPU only: `fovea validate` runs it too).
class ValidateContext {
public:
    virtual ~ValidateContext() = default;
    virtual bool connected(const std::string& input) const = 0;
    virtual uint32_t width() const = 0;  // render size
    virtual uint32_t height() const = 0;
    virtual uint32_t sceneFeatures() const = 0;  // SceneFeature bits of the loaded scene
    // Throws the input error (exit 2) naming the graph file and /passes/<i>/params/<param>.
    [[noreturn]] virtual void fail(const std::string& param, const std::string& message) const = 0;
};

class Pass {
public:
    virtual ~Pass() = default;

    virtual void params(ParamVisitor&) {}
    virtual void reflect(Reflection& r) const = 0;
    virtual uint32_t sceneNeeds() const { return 0; }
    // True when the outputs depend on the frame camera (pose, gaze, eyes) without needing scene
    // geometry: the camera then enters the cache key, and the pass is not culled without a scene.
    // Passes with sceneNeeds() != 0 see the camera anyway.
    virtual bool usesCamera() const { return false; }
    // Checks parameters against each other and against the connected edges during compile (so
    // `fovea validate` rejects what `fovea run` would, with exit 2 and the parameter's pointer).
    virtual void validate(const ValidateContext&) const {}
    virtual void compile(CompileContext&) {}
    virtual void execute(ExecuteContext& ctx) = 0;

    // Frame-level skipping. When isActive() is false the graph copies each bypass pair's input
    // into its output (same size/format required) instead of executing; outputs without a bypass
    // keep their previous content.
    virtual bool isActive(const FrameInfo&) const { return true; }
    virtual std::vector<std::pair<std::string, std::string>> bypass() const { return {}; }
    // A cacheable pass's outputs depend only on its inputs and parameters: when neither changed
    // since its last execution, the graph does not run it again.
    virtual bool cacheable() const { return false; }
    // Called on reset/resize/camera cut so a pass can drop CPU-side temporal state.
    virtual void onReset() {}
    // Which specialization ran (e.g. "lambert,emissive,no-punctual,no-textures,bounces=1"), for
    // reports; empty for passes with a single variant.
    virtual std::string variant() const { return {}; }
    // Counters the pass wants in report.json (e.g. how many NaN inputs it sanitized), read after
    // the last frame (a GPU read-back: only for reports, never per frame). Null = none.
    virtual nlohmann::json statistics(const StatisticsContext&) const { return nullptr; }
    // What evaluation needs to know about this pass's configuration (PassFacts.h), from its
    // parameters as loaded; no device needed. Empty for passes evaluation does not ask about.
    virtual PassFacts facts() const { return {}; }

    const std::string& name() const { return mName; }
    const std::string& type() const { return mType; }
    void setIdentity(std::string name, std::string type) {
        mName = std::move(name);
        mType = std::move(type);
    }

private:
    std::string mName;
    std::string mType;
};

}  // namespace fovea::graph
