// Progress on stderr for long runs: a frame counter, or for references a bar counting samples
// per pixel with the elapsed time and an ETA (the mean time per frame so far times the frames
// left). Redrawn at most twice a second so a fast run is not slowed down by the terminal.
#pragma once
#include <chrono>
#include <cstdint>

namespace fovea::eval {

class Progress {
public:
    // samplesPerFrame = 0: count frames; otherwise show samples per pixel.
    Progress(uint32_t frames, uint32_t samplesPerFrame, bool quiet);
    void update(uint32_t framesDone);
    void finish();

private:
    void draw(uint32_t framesDone);

    uint32_t mFrames, mSamplesPerFrame;
    bool mQuiet, mDrawn = false;
    std::chrono::steady_clock::time_point mStart, mLastDraw;
};

}  // namespace fovea::eval
