// A pass written outside fovea's tree: result = 1 - color (RGB), alpha kept. The smallest
// complete pass: one parameter, one input, one output, one compute shader.
#pragma once
#include <filesystem>
#include <memory>

#include "core/graph/Pass.h"
#include "core/vk/ComputePipeline.h"

class InvertPass : public fovea::graph::Pass {
public:
    // `shaderDir` holds invert/invert.comp: beside the application (main.cpp) or the plugin
    // library (InvertPlugin.cpp).
    explicit InvertPass(std::filesystem::path shaderDir) : mShaderDir(std::move(shaderDir)) {}
    void params(fovea::graph::ParamVisitor& v) override;
    void reflect(fovea::graph::Reflection& r) const override;
    void compile(fovea::graph::CompileContext& ctx) override;
    void execute(fovea::graph::ExecuteContext& ctx) override;

private:
    std::filesystem::path mShaderDir;
    float mWhite{};  // default in params(), applied by the registry
    std::unique_ptr<fovea::gpu::ComputePipeline> mPipeline;
};
