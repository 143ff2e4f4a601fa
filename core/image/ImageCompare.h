// Image comparison for golden tests and error reports.
#pragma once
#include "core/image/ImageIO.h"

namespace fovea::image {

struct CompareTolerance {
    double rmse = 1e-4;           // root mean squared error over RGB
    double maxAbs = 1e-3;         // largest absolute channel difference
    double threshold = 1e-2;      // a pixel is "over" when any RGB channel differs by more
    double maxPercentOver = 0.0;  // allowed percentage of pixels over the threshold
};

struct CompareResult {
    double rmse = 0, maxAbs = 0, percentOver = 0;
    bool sizeMismatch = false;
    bool pass(const CompareTolerance& t) const {
        return !sizeMismatch && rmse <= t.rmse && maxAbs <= t.maxAbs &&
               percentOver <= t.maxPercentOver;
    }
};

// Non-finite values count as maximal error (they never pass silently).
CompareResult compareImages(const ImageRGBA& actual, const ImageRGBA& expected, double threshold);
// |actual - expected| per channel, alpha 1.
ImageRGBA differenceImage(const ImageRGBA& actual, const ImageRGBA& expected);

}  // namespace fovea::image
