#include "apps/fovea/ReferenceErrors.h"

#include <algorithm>
#include <cmath>
#include <regex>

#include "apps/fovea/GraphRunner.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"

namespace fovea::app {

namespace fs = std::filesystem;

ReferenceSource::ReferenceSource(const fs::path& path, const std::string& option, uint32_t width,
                                 uint32_t height)
    : mPath(path), mOption(option), mWidth(width), mHeight(height) {
    if (path.empty()) throw InputError(option, "", "no reference given");
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
    auto it = mFiles.find(frame);
    return it == mFiles.end() ? fs::path() : it->second;
}

void ReferenceSource::load(const fs::path& file) {
    mImage = image::readImage(file);  // InputError naming the file when unreadable
    if (mImage.width != mWidth || mImage.height != mHeight)
        throw InputError(file.string(), "",
                         "reference is " + std::to_string(mImage.width) + "x" +
                             std::to_string(mImage.height) + " but the run renders " +
                             std::to_string(mWidth) + "x" + std::to_string(mHeight) + " (" +
                             mOption + ")");
    image::checkFinite(mImage, file.string());
}

const image::ImageRGBA& ReferenceSource::forFrame(uint32_t frame) {
    if (!mPerFrame) return mImage;
    if (mLoadedFrame != frame) {
        requireFrames(frame, frame);
        auto it = mFiles.find(frame);
        if (it == mFiles.end()) throw RuntimeError("ReferenceSource::choose was not called");
        load(it->second);
        mLoadedFrame = frame;
    }
    return mImage;
}

std::string selectComparedOutput(const GraphRunner& runner, const std::string& requested,
                                 const std::string& option) {
    const auto& desc = runner.graph().desc();
    std::vector<std::string> names;
    for (const auto& out : desc.outputs) names.push_back(out.source.str());
    if (requested.empty()) {
        std::string first = runner.firstFloatOutput();
        if (first.empty())
            throw InputError(option, "",
                             "graph '" + desc.file +
                                 "' has no live float output to compare; name one of its "
                                 "outputs with " +
                                 option);
        return first;
    }
    if (std::find(names.begin(), names.end(), requested) == names.end()) {
        std::string list;
        for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
        throw InputError(option, "",
                         "'" + requested + "' is not an output of graph '" + desc.file + "'" +
                             didYouMean(requested, names) + " (outputs: " + list + ")");
    }
    if (!runner.alive(requested))
        throw InputError(option, "", "output '" + requested + "' is culled in this run");
    return requested;
}

void FrameErrors::add(uint32_t frame, const image::ImageRGBA& test, const std::string& testName,
                      const image::ImageRGBA& reference, const std::string& referenceName,
                      const scene::FrameCamera* camera) {
    Frame f{frame,
            referenceName,
            image::computeMetrics(test, reference, mOptions, testName, referenceName),
            std::nullopt,
            {}};
    // computeMetrics has checked the sizes (InputError otherwise).
    if (camera) f.bands = sampling::eccentricityBandErrors(test, reference, *camera);
    if (mPrevious) f.temporal = image::temporalError(*mPrevious, test, "previous frame", testName);
    mFrames.push_back(std::move(f));
    mPrevious = test;
}

image::ImageMetrics FrameErrors::mean() const {
    image::ImageMetrics m;
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
    const double n = double(mFrames.size());  // >= 1 here
    for (double* v :
         {&m.mse, &m.rmse, &m.rmsePercent, &m.relMse, &m.psnr, &m.ssim, &m.meanAbsLuminanceDiff})
        *v /= n;
    return m;
}

std::vector<sampling::BandError> FrameErrors::meanBands() const {
    std::vector<sampling::BandError> mean;
    size_t n = 0;
    for (const auto& f : mFrames) {
        if (f.bands.empty()) continue;
        if (mean.empty()) {
            mean = f.bands;
            for (auto& b : mean) b.rmse = 0;
        }
        for (size_t b = 0; b < mean.size() && b < f.bands.size(); ++b)
            mean[b].rmse += f.bands[b].rmse;
        ++n;
    }
    for (auto& b : mean) b.rmse /= double(std::max<size_t>(n, 1));
    return mean;
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
        json j = image::metricsToJson(f.metrics, mOptions);
        j["frame"] = f.frame;
        j["reference"] = f.reference;
        j["temporal_error"] = f.temporal ? json(*f.temporal) : json(nullptr);
        if (!f.bands.empty()) j["bands"] = sampling::bandErrorsToJson(f.bands);
        frames.push_back(j);
    }
    json mean = image::metricsToJson(this->mean(), mOptions);
    mean.erase("temporal_error");  // per frame it is against the previous frame, see below
    if (auto bands = meanBands(); !bands.empty()) mean["bands"] = sampling::bandErrorsToJson(bands);
    return {{"frames", frames}, {"mean", mean}, {"temporal_error", temporalError()}};
}

}  // namespace fovea::app
