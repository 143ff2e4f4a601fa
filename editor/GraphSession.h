// What the inspector drives: a built graph with its scene and camera, implemented by the
// `fovea inspect` command (apps/fovea/InspectCommand.cpp), so editor/ depends on core/ only.
#pragma once
#include <array>
#include <glm/glm.hpp>
#include <optional>
#include <string>

#include "core/graph/GraphDesc.h"
#include "core/graph/RenderGraph.h"
#include "core/scene/Scene.h"

namespace fovea::gpu {
class Context;
}

namespace fovea::editor {

using Gaze = std::array<glm::vec2, 2>;  // per eye, in [0,1]^2 of that eye's image

// What the inspector asks of the next frame.
struct FrameRequest {
    std::optional<Gaze> gaze;                 // replaces the camera path's (or --gaze) gaze points
    std::optional<scene::CameraDesc> camera;  // free-fly: replaces the camera path's pose
};

class GraphSession {
public:
    virtual ~GraphSession() = default;
    virtual gpu::Context& gpu() = 0;
    virtual graph::RenderGraph& graph() = 0;
    // The description the graph was last built from successfully.
    virtual const graph::GraphDesc& desc() const = 0;
    virtual const graph::CompileOptions& compileOptions() const = 0;
    virtual bool stereo() const = 0;
    virtual bool hasScene() const = 0;
    // The pose the camera path (or the scene's camera) gives the next frame: where free-fly
    // starts from.
    virtual scene::CameraDesc pathCamera() = 0;
    virtual graph::FrameTiming runFrame(const FrameRequest& request) = 0;
    // Builds `desc` (history rings survive, RenderGraph::build). On failure the last good
    // description is built again and the error rethrown, so the graph keeps running.
    virtual void rebuild(const graph::GraphDesc& desc) = 0;
    // A parameter edit: RenderGraph::update (only changed passes recompile, in place when the
    // plan keeps its shape); on failure like rebuild().
    virtual graph::RenderGraph::UpdateResult update(const graph::GraphDesc& desc) = 0;
    // Parses a graph file with the command line's --set overrides applied. Throws InputError.
    virtual graph::GraphDesc loadGraphFile(const std::string& path) = 0;
};

}  // namespace fovea::editor
