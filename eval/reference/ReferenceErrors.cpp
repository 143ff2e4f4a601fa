#include "eval/reference/ReferenceErrors.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <regex>

#include "core/graph/Param.h"
#include "core/graph/PassRegistry.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"

namespace fovea::eval {

namespace fs = std::filesystem;

ReferenceSource::ReferenceSource(const fs::path& path, const std::string& option, uint32_t width,
                                 uint32_t height)
    : mPath(path), mOption(option), mWidth(width), mHeight(height) {
    if (path.empty()) throw InputError(option, "", "no reference given");
    if (path.string().find('%') != std::string::npos) {
        // One integer conversion (flags and width allowed), "%%" escapes: checked before any
        // frame so that snprintf below never meets another conversion.
        static const std::regex kPattern(R"(^([^%]|%%)*%0?[0-9]*[du]([^%]|%%)*$)");
        if (!std::regex_match(path.string(), kPattern))
            throw InputError(option, "",
                             "reference pattern '" + path.string() +
                                 "' needs exactly one integer conversion such as %04d (the frame "
                                 "number)");
        mPattern = path.string();
        mPerFrame = true;
        return;
    }
    if (!fs::exists(path))
        throw InputError(option, "", "reference '" + path.string() + "' does not exist");
    if (!fs::is_directory(path)) {
        load(path);  // one reference for every frame: checked now, before any frame runs
        return;
    }
    mPerFrame = true;
    static const std::regex kFrame(R"(frame(\d{4,}))");
    for (const auto& entry : fs::directory_iterator(path)) {
        const std::string name = entry.path().filename().string();
        std::smatch m;
        if (!entry.is_regular_file() || entry.path().extension() != ".exr" ||
            !std::regex_search(name, m, kFrame))
            continue;
        mCandidates[uint32_t(std::stoul(m[1]))].push_back(entry.path());
    }
    if (mCandidates.empty())
        throw InputError(option, "",
                         "reference directory '" + path.string() +
                             "' has no per-frame EXR (expected names containing frameNNNN, e.g. "
                             "acc.mean.frame0000.exr)");
}

void ReferenceSource::requireFrames(uint32_t first, uint32_t last) const {
    if (!mPerFrame) return;
    if (!mPattern.empty()) {
        for (uint32_t f = first; f <= last; ++f)
            if (!fs::is_regular_file(fileFor(f)))
                throw InputError(mOption, "",
                                 "reference pattern '" + mPattern + "' gives no file for frame " +
                                     std::to_string(f) + " ('" + fileFor(f).string() +
                                     "' not found)");
        return;
    }
    for (uint32_t f = first; f <= last; ++f)
        if (!mCandidates.count(f)) {
            char name[32];
            std::snprintf(name, sizeof name, "frame%04u", f);
            throw InputError(mOption, "",
                             "reference directory '" + mPath.string() + "' has no EXR for frame " +
                                 std::to_string(f) + " (no file name containing '" + name + "')");
        }
}

void ReferenceSource::choose(const std::string& output) {
    mFiles.clear();
    mLoadedFrame.reset();
    if (!mPattern.empty()) return;  // one file per frame by construction
    for (auto& [frame, files] : mCandidates) {
        std::sort(files.begin(), files.end());
        std::vector<fs::path> named;
        for (const auto& f : files)
            if (f.filename().string().rfind(output + ".frame", 0) == 0) named.push_back(f);
        if (files.size() == 1 || named.size() == 1) {
            mFiles[frame] = files.size() == 1 ? files.front() : named.front();
            continue;
        }
        std::string list;
        for (const auto& f : files)
            list += (list.empty() ? "'" : ", '") + f.filename().string() + "'";
        throw InputError(mOption, "",
                         "reference directory '" + mPath.string() + "' has " +
                             std::to_string(files.size()) + " files for frame " +
                             std::to_string(frame) + " (" + list +
                             "); keep one per frame or name "
                             "it '" +
                             output + ".frameNNNN.exr' after the compared output");
    }
}

fs::path ReferenceSource::fileFor(uint32_t frame) const {
    if (!mPerFrame) return mPath;
    if (!mPattern.empty()) {
        // The constructor checked: one %d/%u conversion, so one unsigned argument is right.
        std::vector<char> text(mPattern.size() + 32);
        std::snprintf(text.data(), text.size(), mPattern.c_str(), frame);
        return fs::path(text.data());
    }
    auto it = mFiles.find(frame);
    return it == mFiles.end() ? fs::path() : it->second;
}

void ReferenceSource::load(const fs::path& file) {
    // The header first (InputError naming the file when unreadable): a wrong size is refused
    // before the decode allocates anything.
    const image::ImageSize header = image::readImageSize(file);
    if (header.width != mWidth || header.height != mHeight)
        throw InputError(file.string(), "",
                         "reference is " + std::to_string(header.width) + "x" +
                             std::to_string(header.height) + " but the run renders " +
                             std::to_string(mWidth) + "x" + std::to_string(mHeight) + " (" +
                             mOption + ")");
    mImage = image::readImage(file);
    if (mImage.width != mWidth || mImage.height != mHeight)
        throw InputError(file.string(), "", "the reference changed size while it was read");
    eval::checkFinite(mImage, file.string());
}

const image::ImageRGBA& ReferenceSource::forFrame(uint32_t frame) {
    if (!mPerFrame) return mImage;
    if (mLoadedFrame != frame) {
        requireFrames(frame, frame);
        const fs::path file = fileFor(frame);
        if (file.empty()) throw RuntimeError("ReferenceSource::choose was not called");
        load(file);
        mLoadedFrame = frame;
    }
    return mImage;
}

graph::PassFacts passFactsOf(const graph::PassDesc& p, const std::string& file) {
    if (!p.enabled || !graph::passRegistry().find(p.type)) return {};
    auto pass = graph::passRegistry().create(p.type, p.name);
    graph::loadParams(*pass, p.params, file, p.pointer + "/params");
    return pass->facts();
}

std::optional<eval::LayerRadii> foveationRadiiOf(const graph::GraphDesc& desc) {
    for (const auto& p : desc.passes)
        if (auto layers = passFactsOf(p, desc.file).foveationLayers) return *layers;
    return std::nullopt;
}

bool parseFlipPpd(const std::string& text, FlipChoice& choice) {
    if (text == "camera") {
        choice.ppdFromCamera = true;
        return true;
    }
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v) || !(v > 0)) return false;
    choice.ppd = v;
    choice.ppdFromCamera = false;
    return true;
}

void FrameErrors::setFlip(const FlipChoice& choice, bool displayEncoded) {
    if (!choice.enabled) {
        mFlip.reset();
        return;
    }
    eval::FlipOptions options;
    options.mode = choice.mode == "ldr"   ? eval::FlipMode::Ldr
                   : choice.mode == "hdr" ? eval::FlipMode::Hdr
                   : displayEncoded       ? eval::FlipMode::Ldr
                                          : eval::FlipMode::Hdr;
    options.pixelsPerDegree = choice.ppd;
    mFlip = options;
    mFlipPpdFromCamera = choice.ppdFromCamera;
}

void FrameErrors::add(uint32_t frame, const image::ImageRGBA& test, const std::string& testName,
                      const image::ImageRGBA& reference, const std::string& referenceName,
                      const scene::FrameCamera* camera) {
    Frame f{frame,
            referenceName,
            eval::computeMetrics(test, reference, mOptions, testName, referenceName),
            std::nullopt,
            {},
            {},
            nullptr};
    // computeMetrics has checked the sizes and values (InputError otherwise).
    std::optional<eval::FlipResult> flip;
    if (mFlip) {
        eval::FlipOptions options = *mFlip;
        if (mFlipPpdFromCamera && camera)
            options.pixelsPerDegree = eval::cameraPixelsPerDegree(*camera, test.width, test.height);
        flip = eval::computeFlip(test, reference, options, testName, referenceName);
        f.metrics.flipMean = flip->mean;
        f.flip = eval::flipSettingsToJson(*flip);
    }
    const std::vector<float>* flipMap = flip ? &flip->errors : nullptr;
    if (camera) f.bands = eval::eccentricityBandErrors(test, reference, *camera, flipMap);
    if (camera && mLayers)
        f.layers = eval::foveationLayerErrors(test, reference, *camera, *mLayers, flipMap);
    if (mPrevious) f.temporal = eval::temporalError(*mPrevious, test, "previous frame", testName);
    mFrames.push_back(std::move(f));
    mPrevious = test;
}

eval::ImageMetrics FrameErrors::mean() const {
    eval::ImageMetrics m;
    if (mFrames.empty()) return m;
    m.width = mFrames.front().metrics.width;
    m.height = mFrames.front().metrics.height;
    for (const auto& f : mFrames) {
        m.mse += f.metrics.mse;
        m.rmse += f.metrics.rmse;
        m.rmsePercent += f.metrics.rmsePercent;
        m.relMse += f.metrics.relMse;
        m.psnr += f.metrics.psnr;  // +inf stays +inf: one identical frame
        m.ssim += f.metrics.ssim;
        m.meanAbsLuminanceDiff += f.metrics.meanAbsLuminanceDiff;
    }
    // Every frame has ꟻLIP or none has (setFlip comes before add): NaN stays NaN.
    m.flipMean = 0;
    for (const auto& f : mFrames) m.flipMean += f.metrics.flipMean;
    const double n = double(mFrames.size());  // >= 1 here
    for (double* v : {&m.mse, &m.rmse, &m.rmsePercent, &m.relMse, &m.psnr, &m.ssim,
                      &m.meanAbsLuminanceDiff, &m.flipMean})
        *v /= n;
    return m;
}

std::vector<eval::BandError> FrameErrors::meanRegions(std::vector<eval::BandError> Frame::*regions,
                                                      bool rms) const {
    std::vector<eval::BandError> mean;
    size_t n = 0;
    for (const auto& f : mFrames) {
        const auto& frame = f.*regions;
        if (frame.empty()) continue;
        if (mean.empty()) {
            mean = frame;
            for (auto& r : mean) r.rmse = r.flipMean = 0;
        }
        for (size_t r = 0; r < mean.size() && r < frame.size(); ++r) {
            mean[r].rmse += rms ? frame[r].rmse * frame[r].rmse : frame[r].rmse;
            mean[r].flipMean += frame[r].flipMean;  // a plain mean; NaN (no ꟻLIP) stays NaN
        }
        ++n;
    }
    const double count = double(std::max<size_t>(n, 1));
    for (auto& r : mean) {
        r.rmse = rms ? std::sqrt(r.rmse / count) : r.rmse / count;
        r.flipMean /= count;
    }
    return mean;
}

std::vector<eval::BandError> FrameErrors::meanBands() const {
    return meanRegions(&Frame::bands, false);
}

std::vector<eval::BandError> FrameErrors::meanLayers() const {
    return meanRegions(&Frame::layers, true);
}

std::optional<uint32_t> FrameErrors::worstFrame() const {
    const Frame* worst = nullptr;
    for (const auto& f : mFrames)
        if (!worst || f.metrics.rmse > worst->metrics.rmse) worst = &f;
    return worst ? std::optional<uint32_t>(worst->frame) : std::nullopt;
}

const eval::ImageMetrics& FrameErrors::metricsOf(uint32_t frame) const {
    for (const auto& f : mFrames)
        if (f.frame == frame) return f.metrics;
    throw RuntimeError("FrameErrors: no frame " + std::to_string(frame));
}

double FrameErrors::temporalError() const {
    double sum = 0;
    size_t pairs = 0;
    for (const auto& f : mFrames)
        if (f.temporal) {
            sum += *f.temporal;
            ++pairs;
        }
    return pairs ? sum / double(pairs) : 0.0;
}

nlohmann::json FrameErrors::json() const {
    using nlohmann::json;
    json frames = json::array();
    for (const auto& f : mFrames) {
        json j = eval::metricsToJson(f.metrics, mOptions);
        j["frame"] = f.frame;
        j["reference"] = f.reference;
        j["temporal_error"] = f.temporal ? json(*f.temporal) : json(nullptr);
        if (!f.bands.empty()) j["bands"] = eval::bandErrorsToJson(f.bands);
        if (!f.layers.empty() && mLayers) j["layers"] = eval::layerErrorsToJson(f.layers, *mLayers);
        if (!f.flip.is_null()) j["flip"] = f.flip;
        frames.push_back(j);
    }
    json mean = eval::metricsToJson(this->mean(), mOptions);
    mean.erase("temporal_error");  // per frame it is against the previous frame, see below
    if (auto bands = meanBands(); !bands.empty()) mean["bands"] = eval::bandErrorsToJson(bands);
    if (auto layers = meanLayers(); !layers.empty() && mLayers)
        mean["layers"] = eval::layerErrorsToJson(layers, *mLayers);
    json out = {{"frames", frames}, {"mean", mean}, {"temporal_error", temporalError()}};
    if (!mFrames.empty() && !mFrames.front().flip.is_null())
        out["flip"] = {{"mode", mFrames.front().flip.at("mode")},
                       {"pixels_per_degree", mFrames.front().flip.at("pixels_per_degree")}};
    if (auto worst = worstFrame()) {
        json w = eval::metricsToJson(metricsOf(*worst), mOptions);
        w.erase("temporal_error");
        w["frame"] = *worst;
        out["worst"] = w;
    }
    return out;
}

}  // namespace fovea::eval
