// What the inspector drives: a built graph with its scene and camera, implemented by the
// `fovea inspect` command (apps/fovea/InspectCommand.cpp), so editor/ depends on core/ only.
#pragma once
#include <array>
#include <glm/glm.hpp>
#include <optional>
#include <string>

#include "core/graph/GraphDesc.h"
#include "core/graph/RenderGraph.h"

namespace fovea::gpu {
class Context;
}

namespace fovea::editor {

using Gaze = std::array<glm::vec2, 2>;  // per eye, in [0,1]^2 of that eye's image

class GraphSession {
public:
    virtual ~GraphSession() = default;
    virtual gpu::Context& gpu() = 0;
    virtual graph::RenderGraph& graph() = 0;
    // The description the graph was last built from successfully.
    virtual const graph::GraphDesc& desc() const = 0;
    virtual const graph::CompileOptions& compileOptions() const = 0;
    virtual bool stereo() const = 0;
    // Runs the next frame; `gaze` replaces the camera path's (or --gaze) gaze points.
    virtual graph::FrameTiming runFrame(const std::optional<Gaze>& gaze) = 0;
    // Builds `desc` (history rings survive, RenderGraph::build). On failure the last good
    // description is built again and the error rethrown, so the graph keeps running.
    virtual void rebuild(const graph::GraphDesc& desc) = 0;
    // Parses a graph file with the command line's --set overrides applied. Throws InputError.
    virtual graph::GraphDesc loadGraphFile(const std::string& path) = 0;
};

}  // namespace fovea::editor
