// Sample layouts: which pixels a pass traces and with how many samples each
// (docs/sample-layouts.md). A layout is a storage buffer, std430, mirrored by
// shaders/common/sample_layout.glsl:
//     uint count; uint maxSamples; uint pad0; uint pad1;   (16-byte header)
//     uvec2 entries[];   x = px | (py << 16), y = sample count (>= 1; 0 = ignored)
// This is seed 000's "coordinates buffer" (§3.2, §4.1): the list of pixels, in the coordinates of
// the whole side-by-side stereo image, that the path tracer launches rays for. Passes read the
// graph field `layout`; in GLSL the block is `sample_layout` because `layout` is a keyword, so a
// pass binds it with ExecuteContext::bindField (an open input gets the graph's zero buffer).
#pragma once
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace fovea::gpu {
class Buffer;
class ComputePipeline;
class Context;
}  // namespace fovea::gpu

namespace fovea::sampling {

struct SampleLayoutHeader {
    uint32_t count = 0;       // entries that follow (a reader clamps it to the buffer's length)
    uint32_t maxSamples = 0;  // largest entry sample count (a hint; readers never trust it)
    uint32_t pad0 = 0, pad1 = 0;
};
struct SampleLayoutEntry {
    uint32_t pixel = 0;    // x | (y << 16)
    uint32_t samples = 0;  // >= 1; 0 = ignored
};
static_assert(sizeof(SampleLayoutHeader) == 16 && sizeof(SampleLayoutEntry) == 8);

inline constexpr uint64_t kSampleLayoutHeaderBytes = sizeof(SampleLayoutHeader);
inline constexpr uint64_t kSampleLayoutEntryBytes = sizeof(SampleLayoutEntry);
inline constexpr uint32_t kSampleLayoutMaxCoordinate = 0xFFFFu;  // 16 bits per axis
// The graph field name and the GLSL block instance name (shaders/common/sample_layout.glsl).
inline constexpr const char* kSampleLayoutField = "layout";
inline constexpr const char* kSampleLayoutBinding = "sample_layout";

// Throws InputError when a width x height image has coordinates a layout cannot store.
void checkSampleLayoutSize(uint32_t width, uint32_t height);

inline uint64_t sampleLayoutBytes(uint64_t entries) {
    return kSampleLayoutHeaderBytes + entries * kSampleLayoutEntryBytes;
}
inline uint32_t packSamplePixel(uint32_t x, uint32_t y) {
    return (x & 0xFFFFu) | (y << 16);
}
inline glm::uvec2 unpackSamplePixel(uint32_t packed) {
    return {packed & 0xFFFFu, packed >> 16};
}

// A layout on the CPU: tests build expected lists with it and parse what a pass produced.
struct SampleLayout {
    std::vector<SampleLayoutEntry> entries;

    void add(uint32_t x, uint32_t y, uint32_t samples) {
        entries.push_back({packSamplePixel(x, y), samples});
    }
    uint32_t maxSamples() const;
    uint64_t totalSamples() const;
    // The buffer image: header (count = entries.size(), maxSamples) + entries.
    std::vector<std::byte> bytes() const;
    // Reads a downloaded buffer; the count is clamped to what the bytes hold. Throws
    // RuntimeError when fewer than 16 bytes are given.
    static SampleLayout parse(const std::vector<std::byte>& bytes);
};

// The patterns of the SampleList pass, computed on the CPU exactly as its shader does (same
// selection rule, same hash, row-major order over the whole side-by-side image).
enum class SamplePattern { All, Checkerboard, EveryNth, Random };

struct SamplePatternOptions {
    SamplePattern pattern = SamplePattern::All;
    uint32_t n = 2;         // EveryNth: linear pixel index % n == 0
    float fraction = 0.5f;  // Random: probability of selecting a pixel, in [0, 1]
    uint32_t seed = 0;      // Random: mixes the graph seed and (optionally) the frame index
    uint32_t samples = 1;   // per listed pixel
};

// 32-bit threshold for the Random pattern: a pixel is selected when its hash < threshold.
// fraction 1 selects everything (threshold saturates; the shader treats 0xFFFFFFFF specially).
uint32_t sampleFractionThreshold(float fraction);
// The hash the shader uses: hashCombine(seed, pixelIndex) of shaders/common/random.glsl.
uint32_t sampleListHash(uint32_t pixelIndex, uint32_t seed);
// The Random pattern's 32-bit seed from the graph seed and, when animated, the frame index.
uint32_t sampleListSeed(uint64_t graphSeed, uint64_t frameIndex, bool animate);
// The selection rule of one pixel (x, y) of a width x height image.
bool samplePatternSelects(const SamplePatternOptions& o, uint32_t x, uint32_t y, uint32_t width);
SampleLayout buildSampleLayout(const SamplePatternOptions& o, uint32_t width, uint32_t height);

// Problems of a layout for a width x height image, one line each (empty = valid): entries
// outside the image, sample count 0, duplicated pixels. Passes tolerate all of them (ignored
// entries; a duplicated pixel is traced twice, last write wins), but producers should not emit
// them.
std::vector<std::string> validateSampleLayout(const SampleLayout& layout, uint32_t width,
                                              uint32_t height);

}  // namespace fovea::sampling
