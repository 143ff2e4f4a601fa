#include "eval/run/Progress.h"

#include <cstdio>
#include <string>

namespace fovea::eval {

namespace {
double secondsSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}
}  // namespace

Progress::Progress(uint32_t frames, uint32_t samplesPerFrame, bool quiet)
    : mFrames(frames),
      mSamplesPerFrame(samplesPerFrame),
      mQuiet(quiet),
      mStart(std::chrono::steady_clock::now()),
      mLastDraw(mStart) {}

void Progress::update(uint32_t framesDone) {
    if (mQuiet || mFrames <= 1) return;
    const bool last = framesDone >= mFrames;
    // Only runs longer than a second show progress at all; then at most two redraws a second.
    if (!last && (secondsSince(mStart) < 1.0 || secondsSince(mLastDraw) < 0.5)) return;
    if (last && !mDrawn && mSamplesPerFrame == 0 && secondsSince(mStart) < 1.0) return;
    draw(framesDone);
}

void Progress::draw(uint32_t framesDone) {
    mLastDraw = std::chrono::steady_clock::now();
    mDrawn = true;
    const double elapsed = secondsSince(mStart);
    // framesDone >= 1 whenever update() is called, so the mean frame time is defined.
    const double eta = elapsed / double(framesDone) * double(mFrames - framesDone);
    if (mSamplesPerFrame == 0) {
        std::fprintf(stderr, "\rfovea: frame %u/%u  %.1f s, ETA %.0f s   ", framesDone, mFrames,
                     elapsed, eta);
    } else {
        constexpr int kWidth = 30;
        const int filled = int(double(kWidth) * framesDone / mFrames);  // mFrames > 1 here
        std::string bar(size_t(filled), '#');
        bar.resize(kWidth, '.');
        std::fprintf(stderr, "\rfovea: [%s] %llu/%llu spp  %.1f s, ETA %.0f s   ", bar.c_str(),
                     static_cast<unsigned long long>(framesDone) * mSamplesPerFrame,
                     static_cast<unsigned long long>(mFrames) * mSamplesPerFrame, elapsed, eta);
    }
    std::fflush(stderr);
}

void Progress::finish() {
    if (mDrawn) std::fputc('\n', stderr);
}

}  // namespace fovea::eval
