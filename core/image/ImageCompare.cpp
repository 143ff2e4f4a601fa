#include "core/image/ImageCompare.h"

#include <cmath>
#include <limits>

namespace fovea::image {

CompareResult compareImages(const ImageRGBA& actual, const ImageRGBA& expected, double threshold) {
    CompareResult r;
    if (actual.width != expected.width || actual.height != expected.height) {
        r.sizeMismatch = true;
        r.rmse = r.maxAbs = std::numeric_limits<double>::infinity();
        r.percentOver = 100;
        return r;
    }
    const size_t pixels = size_t(actual.width) * actual.height;
    double sumSq = 0;
    size_t over = 0;
    for (size_t p = 0; p < pixels; ++p) {
        bool isOver = false;
        for (int c = 0; c < 3; ++c) {
            double d = double(actual.pixels[p * 4 + c]) - expected.pixels[p * 4 + c];
            if (!std::isfinite(d)) d = std::numeric_limits<double>::infinity();
            sumSq += d * d;
            r.maxAbs = std::max(r.maxAbs, std::abs(d));
            isOver |= std::abs(d) > threshold;
        }
        over += isOver;
    }
    // pixels >= 1 is not guaranteed (0x0 images): guard the divisions.
    r.rmse = pixels ? std::sqrt(sumSq / double(pixels * 3)) : 0.0;
    r.percentOver = pixels ? 100.0 * double(over) / double(pixels) : 0.0;
    return r;
}

ImageRGBA differenceImage(const ImageRGBA& actual, const ImageRGBA& expected) {
    ImageRGBA d;
    d.width = std::min(actual.width, expected.width);
    d.height = std::min(actual.height, expected.height);
    d.pixels.assign(size_t(d.width) * d.height * 4, 1.0f);
    for (uint32_t y = 0; y < d.height; ++y)
        for (uint32_t x = 0; x < d.width; ++x)
            for (int c = 0; c < 3; ++c) {
                size_t i = (size_t(y) * d.width + x) * 4 + c;
                size_t ia = (size_t(y) * actual.width + x) * 4 + c;
                size_t ie = (size_t(y) * expected.width + x) * 4 + c;
                d.pixels[i] = std::abs(actual.pixels[ia] - expected.pixels[ie]);
            }
    return d;
}

}  // namespace fovea::image
