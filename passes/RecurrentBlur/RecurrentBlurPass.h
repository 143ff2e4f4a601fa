// RecurrentBlur: the ReBLUR diffuse denoiser of seed 004 (the ReBLUR talk, docs/references.md;
// NRD defaults and oracles in docs/passes/RecurrentBlur.md) as two stages of one pass type, so that
// HistoryFix (a separate pass) can sit between them and the recurrence is an edge of the graph:
//
//   rbt: RecurrentBlur{stage: temporal}  pre-blur -> temporal accumulation (+ firefly suppressor)
//   hf:  HistoryFix                      rebuilds pixels with few accumulated frames
//   rbs: RecurrentBlur{stage: spatial}   blur (radius shrinks with N) -> post-blur -> stabilization
//   rbs.history --delay 1--> rbt.history  (the post-blurred output is the recurrent history)
//
// Each stage keeps its private state as pass-declared history: the temporal stage its geometry
// and frame count (`geo`), the spatial stage its stabilized luminance (`stabilized`).
#pragma once
#include <glm/vec3.hpp>
#include <string>

#include "core/graph/Pass.h"

namespace fovea::passes {

class RecurrentBlurPass : public graph::Pass {
public:
    void params(graph::ParamVisitor& v) override;
    void reflect(graph::Reflection& r) const override;
    void validate(const graph::ValidateContext& ctx) const override;
    void compile(graph::CompileContext& ctx) override;
    void execute(graph::ExecuteContext& ctx) override;
    bool usesCamera() const override { return true; }  // frustum size, eyes, view vector
    std::string variant() const override {
        return mStage + (mSignal == "specular" ? ",specular" : "");
    }

private:
    // The image size and its side-by-side eye split (taps never cross the seam).
    struct EyeLayout {
        glm::ivec2 size;
        int eyeWidth, eyes;
    };
    static EyeLayout eyeLayout(const gpu::Image& out, int eyesParam, uint32_t cameraEyes);
    float resolutionScale(const EyeLayout& e) const;  // H / referenceHeight, or 1
    // One blur.comp dispatch (mode 0 pre-blur, 1 blur, 2 post-blur) from fields src/hit to dst.
    void blur(graph::ExecuteContext& ctx, const EyeLayout& e, const char* src, const char* hit,
              const char* dst, int mode, float maxRadius);
    void executeTemporal(graph::ExecuteContext& ctx);
    void executeSpatial(graph::ExecuteContext& ctx);
    void setBlurConstants(graph::ExecuteContext& ctx, int mode, float maxRadius);

    std::string mStage = "temporal";
    std::string mSignal = "diffuse";
    bool mHitNormalized = false;
    bool mVirtualMotion = true;
    float mSpecAccumBasePower = 0.66f;
    float mSpecAccumCurve = 1.0f;
    float mParallaxFrameRate = 60.0f;
    float mHitRadiusK = 0.5f;
    int mMaxAccumulatedFrames = 30;
    int mHistoryFixFrames = 3;
    float mMaxBlurRadius = 30.0f;
    float mMinBlurRadius = 1.0f;
    float mPrepassBlurRadius = 30.0f;
    float mReferenceHeight = 1080.0f;
    std::string mRadiusScaling = "sqrt";
    float mPlaneDistanceSensitivity = 0.02f;
    float mDisocclusionThreshold = 0.01f;
    float mDisocclusionNormal = 0.5f;
    float mMinHitDistanceWeight = 0.1f;
    bool mFireflySuppression = true;
    int mMaxStabilizedFrames = 63;
    bool mAntilag = true;
    float mAntilagSigmaScale = 4.0f;
    float mAntilagSensitivity = 3.0f;
    int mEyes = 0;
    bool mUseMotion = false;
    std::unique_ptr<gpu::ComputePipeline> mBlur, mTemporal, mStabilize;
    // Temporal stage, specular parallax: the eyes of the frame before (none after a compile).
    glm::vec3 mPreviousEyes[2] = {};
    bool mHavePreviousEyes = false;
};

}  // namespace fovea::passes
