// Shared by the PathTrace GPU tests: scenes loaded and uploaded once per process (created after,
// so destroyed before, the shared GPU context of GpuTest) and a graph built from JSON text on one
// of them.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/scene/SceneGpu.h"
#include "tests/graph/GpuTestFixture.h"

namespace fovea::test {

struct LoadedScene {
    scene::Scene scene;
    std::unique_ptr<scene::SceneGpu> gpu;
    scene::CameraDesc camera;  // the scene's first camera, else its default framing
};

// The scene `name` from `load(name)` on first use, then the cached one.
inline LoadedScene& loadedScene(const std::string& name,
                                const std::function<scene::Scene(const std::string&)>& load) {
    static std::map<std::string, std::unique_ptr<LoadedScene>> scenes;
    auto& slot = scenes[name];
    if (!slot) {
        slot = std::make_unique<LoadedScene>();
        slot->scene = load(name);
        slot->gpu = std::make_unique<scene::SceneGpu>(sharedGpuContext(), slot->scene);
        slot->camera =
            slot->scene.cameras.empty() ? slot->scene.defaultCamera() : slot->scene.cameras.front();
    }
    return *slot;
}

// `text` (a graph file's JSON, named `graphName` in errors) built at width x height on `s`.
inline std::unique_ptr<graph::RenderGraph> buildSceneGraph(const LoadedScene& s,
                                                           const std::string& text,
                                                           const std::string& graphName,
                                                           uint64_t seed, uint32_t width,
                                                           uint32_t height) {
    graph::CompileOptions o;
    o.width = width;
    o.height = height;
    o.sceneFeatures = s.gpu->features();
    auto g = std::make_unique<graph::RenderGraph>(sharedGpuContext(), graph::passRegistry());
    g->setScene(s.gpu.get());
    g->build(graph::parseGraphText(text, graphName), o);
    g->setSeed(seed);
    return g;
}

}  // namespace fovea::test
