// PathTrace: the 1 spp ray configuration of seed 003 (P2 §3.1, P5 §3.1) used by seed 000 (§3.3):
// primary hit (GBuffer `visibility` or own jittered camera rays), next-event estimation, one
// cosine/BRDF-sampled indirect bounce (`maxBounces`, default 1) with next-event estimation at its
// hit. Outputs radiance (a = samples), albedo-demodulated radiance, the first indirect hit
// distance, the direct/indirect split and the diffuse/specular split (issue 26). Optional sample
// layout (seed 000 §3.2 coordinates buffer). docs/passes/PathTrace.md.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "core/graph/Pass.h"

namespace fovea::sampling {}

namespace fovea::passes {

class PathTracePass : public graph::Pass {
public:
    PathTracePass();
    ~PathTracePass() override;

    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    uint32_t sceneNeeds() const override { return graph::kSceneGeometry; }
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    // Random per frame and seed: never cacheable (the default).
    std::string variant() const override { return mVariant; }

    // Ray kinds counted with countRays: primary, shadow from the primary hit, indirect, shadow
    // from indirect hits, the last vertex's emitter-seeking BRDF ray (lastBounceMis).
    static constexpr size_t kRayKinds = 5;
    using RayCounts = std::array<uint64_t, kRayKinds>;
    // The counts in the pass's `rays` buffer (RenderGraph::buffer("<pass>.rays")): with countRays
    // on, rays traced since the last compile (build), by kind; zeros otherwise. Waits for the GPU.
    static RayCounts rayCounts(const gpu::Context& context, const gpu::Buffer& rays);
    // report.json: the same counts (with countRays on), by kind and in total.
    nlohmann::json statistics(const graph::StatisticsContext& ctx) const override;
    // `spp` per frame (a reference graph's frame count; with a sample layout the layout decides,
    // which reference graphs do not use).
    graph::PassFacts facts() const override {
        graph::PassFacts facts;
        facts.samplesPerFrame = uint32_t(mSpp);
        return facts;
    }

private:
    // Default of lastBounceMis: see docs/passes/PathTrace.md "Emission and MIS".
    static constexpr bool kLastBounceMisDefault = false;
    int mSpp{};
    int mMaxBounces{};
    std::string mBrdf{};
    float mClampIndirect{};
    bool mCountRays{};
    bool mLastBounceMis{};
    bool mStratifyLight{};
    bool mBumpShadowing{};
    std::string mEmitterSampling{};
    std::string mLightSampling{};

    std::string mVariant;
    bool mUseVisibility = false, mUseAlbedo = false, mUseLayout = false;
    std::unique_ptr<gpu::ComputePipeline> mTrace;
    std::unique_ptr<gpu::ComputePipeline> mClear;
    bool mCountersWritten = false;  // countRays and executed since compile: `rays` is counting
};

}  // namespace fovea::passes
