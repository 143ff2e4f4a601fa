// RecurrentBlur: the ReBLUR denoiser of seed 004 (the ReBLUR talk, docs/references.md; NRD
// defaults and oracles in docs/passes/RecurrentBlur.md) as two pass types, so that HistoryFix (a
// separate pass) can sit between them and the recurrence is an edge of the graph:
//
//   rbt: RecurrentBlurTemporal  pre-blur -> temporal accumulation (+ firefly suppressor)
//   hf:  HistoryFix             rebuilds pixels with few accumulated frames
//   rbs: RecurrentBlurSpatial   blur (radius shrinks with N) -> post-blur -> stabilization
//   rbs.history --delay 1--> rbt.history  (the post-blurred output is the recurrent history)
//
// This base holds what both stages share: the signal, the blur kernel's parameters and its
// dispatch (shaders/recurrent_blur/blur.comp, modes 0-2), the G-buffer inputs and their checks.
// Each stage keeps its private state as pass-declared history: the temporal stage its geometry
// and frame count (`geo`), the spatial stage its stabilized luminance (`stabilized`).
#pragma once
#include <glm/vec2.hpp>
#include <memory>
#include <string>

#include "core/graph/Pass.h"

namespace fovea::passes {

class RecurrentBlurStage : public graph::Pass {
public:
    bool usesCamera() const override { return true; }  // frustum size, eyes, view vector
    std::string variant() const override {
        return mStageName + (mSignal == "specular" ? ",specular" : "");
    }

protected:
    explicit RecurrentBlurStage(std::string stageName) : mStageName(std::move(stageName)) {}
    // The parameters both stages read (declared first on each type's page).
    void sharedParams(graph::ParamVisitor& v);
    // The G-buffer inputs, sized like the stage's main input `ref`.
    void sharedInputs(graph::Reflection& r, const char* ref) const;
    void sharedValidate(const graph::ValidateContext& ctx) const;
    // Creates the blur pipeline; the stage's own pipelines are made by the stage.
    std::vector<std::pair<std::string, std::string>> compileBlur(graph::CompileContext& ctx);

    // The image size and its side-by-side eye split (taps never cross the seam).
    struct EyeLayout {
        glm::ivec2 size;
        int eyeWidth, eyes;
    };
    EyeLayout eyeLayout(const graph::ExecuteContext& ctx, const gpu::Image& out) const;
    float resolutionScale(const EyeLayout& e) const;  // H / referenceHeight, or 1
    // One blur.comp dispatch (mode 0 pre-blur, 1 blur, 2 post-blur) from fields src/hit to dst
    // (the context orders it after the kernel that wrote src). historyFixFrames and
    // hitNormalized are the calling stage's (mode 0 ignores the first, modes 1-2 the second).
    void blur(graph::ExecuteContext& ctx, const EyeLayout& e, const char* src, const char* hit,
              const char* dst, int mode, float maxRadius, int historyFixFrames, bool hitNormalized);

    std::string mStageName;
    std::string mSignal{};
    int mMaxAccumulatedFrames{};
    float mMaxBlurRadius{};
    float mMinBlurRadius{};
    float mReferenceHeight{};
    std::string mRadiusScaling{};
    float mPlaneDistanceSensitivity{};
    float mMinHitDistanceWeight{};
    float mHitRadiusK{};
    int mEyes{};
    bool mUseMotion = false;
    std::unique_ptr<gpu::ComputePipeline> mBlur;
};

}  // namespace fovea::passes
