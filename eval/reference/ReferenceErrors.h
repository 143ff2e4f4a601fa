// Error figures of a graph output against a reference, frame by frame (`run --reference`,
// `bench`): where each frame's reference comes from, which output is compared, and the per-frame
// and mean metrics of eval/metrics/ImageMetrics.h plus the temporal error (docs/report-format.md).
#pragma once
#include <cstdint>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "eval/flip/Flip.h"
#include "eval/metrics/EccentricityBands.h"
#include "eval/metrics/ImageMetrics.h"

namespace fovea::eval {

// What a pass of a graph file reports to evaluation (Pass::facts) with its parameters as given;
// nothing for a disabled pass or a type the registry does not know (compiling the graph reports
// that, with its pointer). Parameter errors are InputErrors naming `file` and the pointer.
graph::PassFacts passFactsOf(const graph::PassDesc& pass, const std::string& file);

// The foveation layer radii of a graph: those its first enabled pass that has layers reports
// (Pass::facts, e.g. FoveationMask's r0, r1 and radiusUnit); none when no pass has.
std::optional<eval::LayerRadii> foveationRadiiOf(const graph::GraphDesc& desc);

// The reference of every frame. `path` is either
//  - an image file (EXR): one converged reference for all frames (a still camera), or
//  - a directory: one file per frame whose name contains `frameNNNN` (4+ digits, the frame
//    number of the run, as `run --save-frames all` names them) and ends in `.exr`: a moving
//    camera path needs a reference per frame. A directory holding several files for one frame (a
//    `run --save-frames all` folder with several outputs) is resolved by choose(): the file
//    named `<compared output>.frameNNNN...` wins, or
//  - a printf pattern with one integer conversion (`ref/tm.ldr.frame%04d.exr`, `%d`, `%05u`):
//    frame f's reference is the pattern printed with f (per-frame references rendered one by
//    one, e.g. by `fovea reference --camera PATH --path-frame F`, docs/benchmarks.md).
// `option` names the source in errors (e.g. "--reference" or the bench file's pointer).
class ReferenceSource {
public:
    ReferenceSource(const std::filesystem::path& path, const std::string& option, uint32_t width,
                    uint32_t height);
    bool perFrame() const { return mPerFrame; }
    const std::filesystem::path& path() const { return mPath; }
    // Throws InputError naming the directory when one of frames [first, last] has no file.
    void requireFrames(uint32_t first, uint32_t last) const;
    // Picks each frame's file given the compared output (see above); throws InputError listing
    // the files when a frame stays ambiguous. Needed before forFrame in per-frame mode.
    void choose(const std::string& output);
    std::filesystem::path fileFor(uint32_t frame) const;
    // Reads (and checks size and finiteness of) the reference of `frame`.
    const image::ImageRGBA& forFrame(uint32_t frame);

private:
    std::filesystem::path mPath;
    std::string mOption;
    uint32_t mWidth, mHeight;
    bool mPerFrame = false;
    std::map<uint32_t, std::vector<std::filesystem::path>> mCandidates;  // per-frame mode
    std::map<uint32_t, std::filesystem::path> mFiles;                    // after choose()
    std::string mPattern;  // printf pattern mode: non-empty
    std::optional<uint32_t> mLoadedFrame;
    image::ImageRGBA mImage;
    void load(const std::filesystem::path& file);
};

// How `run --reference` and `bench` evaluate ꟻLIP (docs/metrics.md "ꟻLIP"); on by default.
struct FlipChoice {
    bool enabled = true;
    // "auto": LDR-ꟻLIP for a display-encoded output (8-bit UNORM, e.g. Tonemap's ldr), HDR-ꟻLIP
    // for a linear one; "ldr" | "hdr".
    std::string mode = "auto";
    double ppd = 0;              // 0: ꟻLIP's default observer (67.02 ppd)
    bool ppdFromCamera = false;  // "camera": each frame's camera (eval::cameraPixelsPerDegree)
};
// Reads a pixels-per-degree setting: "camera" or a finite number > 0 into `choice`; false when
// `text` is neither.
bool parseFlipPpd(const std::string& text, FlipChoice& choice);

// Per-frame metrics and the temporal error (Schied et al. 2017: mean |ΔY| between consecutive
// compared frames of the output).
class FrameErrors {
public:
    explicit FrameErrors(eval::MetricOptions options = {}) : mOptions(options) {}
    // With radii (and a camera in add): also the RMSE per foveation layer (fovea / middle /
    // outer, seed 000 §3.2), eval/metrics/EccentricityBands.h.
    void setLayers(const eval::LayerRadii& radii) { mLayers = radii; }
    const std::optional<eval::LayerRadii>& layers() const { return mLayers; }
    // Also ꟻLIP per frame (eval/flip/Flip.h) as `choice` says, its mean per band and layer too.
    // `displayEncoded`: the compared output holds display-encoded values (an 8-bit UNORM image),
    // which mode "auto" evaluates with LDR-ꟻLIP (HDR-ꟻLIP otherwise).
    void setFlip(const FlipChoice& choice, bool displayEncoded);
    // `camera` (the frame's): also the RMSE per eccentricity band (0-5, 5-20, 20+ degrees,
    // eval/metrics/EccentricityBands.h); null = no bands.
    void add(uint32_t frame, const image::ImageRGBA& test, const std::string& testName,
             const image::ImageRGBA& reference, const std::string& referenceName,
             const scene::FrameCamera* camera = nullptr);
    // Mean per-band RMSE over the frames that have bands (empty when none has).
    std::vector<eval::BandError> meanBands() const;
    // Mean per-layer RMSE (RMS over the frames, so that it squares to the mean MSE) over the
    // frames that have layers (empty when none has).
    std::vector<eval::BandError> meanLayers() const;
    // The frame with the largest RMSE (the first of equal ones); 0 frames: none.
    std::optional<uint32_t> worstFrame() const;
    const eval::ImageMetrics& metricsOf(uint32_t frame) const;
    size_t count() const { return mFrames.size(); }
    // Mean of each per-frame figure; PSNR is +inf when any frame's is (identical images).
    eval::ImageMetrics mean() const;
    // Mean temporal error over consecutive pairs; 0 with fewer than two frames.
    double temporalError() const;
    // {"frames": [{"frame", "reference", metrics..., "temporal_error"}], "mean": {...},
    //  "temporal_error"}: the metric keys of metricsToJson; "temporal_error" of a frame is
    // against the previous compared frame (null for the first). With a camera: "bands" per frame
    // and in "mean" ([{"from", "to", "pixels", "rmse"}]); with layers also "layers" (see
    // layerErrorsToJson). "worst": {"frame", metrics...} of worstFrame(). With ꟻLIP: "flip_mean"
    // beside the metrics (per frame, band, layer and in "mean"), "flip" (flipSettingsToJson) per
    // frame and, without the exposures, at the top.
    nlohmann::json json() const;

private:
    struct Frame {
        uint32_t frame;
        std::string reference;
        eval::ImageMetrics metrics;
        std::optional<double> temporal;
        std::vector<eval::BandError> bands;
        std::vector<eval::BandError> layers;
        nlohmann::json flip;  // flipSettingsToJson; null without ꟻLIP
    };
    eval::MetricOptions mOptions;
    // Mean over the frames that have them of each region's figures: RMSE as a mean (rms false)
    // or as the RMS over the frames (so that it squares to the mean MSE), ꟻLIP as a mean.
    std::vector<eval::BandError> meanRegions(std::vector<eval::BandError> Frame::*regions,
                                             bool rms) const;
    std::optional<eval::LayerRadii> mLayers;
    std::optional<eval::FlipOptions> mFlip;
    bool mFlipPpdFromCamera = false;
    std::vector<Frame> mFrames;
    std::optional<image::ImageRGBA> mPrevious;
};

}  // namespace fovea::eval
