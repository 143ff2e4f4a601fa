#include "passes/ImageFile/ImageFilePass.h"

#include <algorithm>
#include <cstring>
#include <sstream>

#include "core/image/ImageIO.h"
#include "core/util/Error.h"
#include "core/vk/Context.h"

namespace fovea::passes {

std::string framePatternError(const std::string& pattern) {
    return "frame pattern '" + pattern +
           "': only one integer conversion (%d, %4d, %04d) is allowed, '%%' is a literal %";
}

std::string formatFramePattern(const std::string& pattern, uint64_t frame,
                               const std::string& what) {
    std::string out;
    int conversions = 0;
    for (size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') {
            out += pattern[i];
            continue;
        }
        size_t j = i + 1;
        if (j < pattern.size() && pattern[j] == '%') {
            out += '%';
            i = j;
            continue;
        }
        const bool zeros = j < pattern.size() && pattern[j] == '0';
        if (zeros) ++j;
        size_t width = 0;
        while (j < pattern.size() && pattern[j] >= '0' && pattern[j] <= '9' && width < 100)
            width = width * 10 + size_t(pattern[j++] - '0');
        if (j >= pattern.size() || pattern[j] != 'd' || width > 32 || ++conversions > 1)
            throw InputError(what, "", framePatternError(pattern));
        std::string number = std::to_string(frame);
        if (number.size() < width) number.insert(0, width - number.size(), zeros ? '0' : ' ');
        out += number;
        i = j;
    }
    return out;
}

void ImageFilePass::params(graph::ParamVisitor& v) {
    v.addPath("path", mPath, std::string(),
              "EXR/PNG file, or a sequence with one printf-style frame number (frame%04d.exr: "
              "frame = firstFrame + frame index); relative to the graph file's folder (from "
              "--set: to the working directory)");
    v.add("firstFrame", mFirstFrame, 0, "number of the file read in the run's first frame",
          {0, 2147483647});
    v.add("channels", mChannels, std::string(),
          "comma list of up to 4 channel names read as r,g,b,a (e.g. albedo.R,albedo.G,albedo.B "
          "of a multi-layer EXR; missing alpha = 1); empty: the file's first channels (grey "
          "replicated)");
}

void ImageFilePass::reflect(graph::Reflection& r) const {
    r.output("color", vk::Format::eR32G32B32A32Sfloat)
        .screen()
        .doc("the file's pixels (must have the render size)");
    r.internal("staging", vk::Format::eUndefined)
        .bufferPerPixel(16)
        .hostVisible()
        .doc("host-visible copy of this frame's pixels (RGBA32F), copied into `color`");
}

std::string ImageFilePass::fileFor(uint64_t frame) const {
    const std::string what = "pass '" + name() + "' (ImageFile) path";
    return formatFramePattern(mResolvedPath, uint64_t(mFirstFrame) + frame, what);
}

std::vector<float> ImageFilePass::readChecked(const std::string& file, uint32_t width,
                                              uint32_t height) const {
    std::vector<std::string> channels;
    std::stringstream list(mChannels);
    for (std::string item; std::getline(list, item, ',');) channels.push_back(item);
    // The header first: a wrong size is refused before the decode allocates anything.
    const image::ImageSize header = image::readImageSize(file);
    if (header.width != width || header.height != height)
        throw InputError(file, "",
                         "the image is " + std::to_string(header.width) + "x" +
                             std::to_string(header.height) + " but pass '" + name() +
                             "' (ImageFile) renders " + std::to_string(width) + "x" +
                             std::to_string(height) + " (--size)");
    image::ImageRGBA img = image::readImageChannels(file, channels);
    if (img.width != width || img.height != height)  // the file changed since the header read
        throw InputError(file, "", "the image changed size while it was read");
    return std::move(img.pixels);
}

// The device-independent checks, so `fovea validate` refuses what `run` would (issue 33, class 4):
// an empty path and a malformed frame pattern, with the parameter's JSON pointer.
void ImageFilePass::validate(const graph::ValidateContext& ctx) const {
    if (mPath.empty()) ctx.fail("path", "'path' is empty: name an image file or a frame pattern");
    try {
        formatFramePattern(mPath, 0, "path");
    } catch (const InputError&) {
        ctx.fail("path", framePatternError(mPath));
    }
    if (std::count(mChannels.begin(), mChannels.end(), ',') > 3)
        ctx.fail("channels", "at most 4 channels can be selected");
}

void ImageFilePass::compile(graph::CompileContext& ctx) {
    if (mPath.empty())
        throw InputError("pass '" + name() + "' (ImageFile)", "", "parameter 'path' is empty");
    mResolvedPath = ctx.resolvePath(mPath);
    const auto& size = ctx.renderSize();
    // The first frame's file is read now: a missing or wrong-size file fails before any frame.
    readChecked(fileFor(0), size.width, size.height);
}

void ImageFilePass::execute(graph::ExecuteContext& ctx) {
    const auto& frame = ctx.frame();
    const std::vector<float> pixels = readChecked(fileFor(frame.index), frame.width, frame.height);
    // Frames are synchronous (RenderGraph waits for each), so the previous copy out of the
    // staging buffer has finished; the host write is visible to the copy at submit.
    const gpu::Buffer& staging = ctx.buffer("staging");
    std::memcpy(staging.mapped(), pixels.data(), pixels.size() * sizeof(float));
    const gpu::Image& target = ctx.image("color");
    vk::BufferImageCopy region{.imageSubresource = {vk::ImageAspectFlagBits::eColor, 0, 0, 1},
                               .imageExtent = vk::Extent3D{frame.width, frame.height, 1}};
    // A transfer write to the pass's own output in GENERAL: the graph's barriers order it
    // (they cover compute and transfer on both sides).
    ctx.cmd().copyBufferToImage(staging.buffer(), target.image(), vk::ImageLayout::eGeneral,
                                region);
}

}  // namespace fovea::passes
