#include "core/sampling/SampleLayout.h"

#include <algorithm>
#include <cstring>
#include <unordered_set>

#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/Context.h"
#include "core/vk/Resources.h"

namespace fovea::sampling {
namespace {

// shaders/common/random.glsl, bit for bit.
uint32_t pcgHash(uint32_t v) {
    uint32_t state = v * 747796405u + 2891336453u;
    uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
uint32_t hashCombine(uint32_t seed, uint32_t v) {
    return pcgHash(seed ^ (v + 0x9e3779b9u + (seed << 6) + (seed >> 2)));
}

}  // namespace

uint32_t SampleLayout::maxSamples() const {
    uint32_t m = 0;
    for (const auto& e : entries) m = std::max(m, e.samples);
    return m;
}

uint64_t SampleLayout::totalSamples() const {
    uint64_t n = 0;
    for (const auto& e : entries) n += e.samples;
    return n;
}

std::vector<std::byte> SampleLayout::bytes() const {
    SampleLayoutHeader h;
    h.count = uint32_t(entries.size());
    h.maxSamples = maxSamples();
    std::vector<std::byte> out(sampleLayoutBytes(entries.size()));
    std::memcpy(out.data(), &h, sizeof(h));
    if (!entries.empty())
        std::memcpy(out.data() + sizeof(h), entries.data(),
                    entries.size() * kSampleLayoutEntryBytes);
    return out;
}

SampleLayout SampleLayout::parse(const std::vector<std::byte>& bytes) {
    if (bytes.size() < kSampleLayoutHeaderBytes)
        throw RuntimeError("sample layout: " + std::to_string(bytes.size()) +
                           " bytes cannot hold the 16-byte header");
    SampleLayoutHeader h;
    std::memcpy(&h, bytes.data(), sizeof(h));
    uint64_t capacity = (bytes.size() - kSampleLayoutHeaderBytes) / kSampleLayoutEntryBytes;
    SampleLayout out;
    out.entries.resize(std::min<uint64_t>(h.count, capacity));
    if (!out.entries.empty())
        std::memcpy(out.entries.data(), bytes.data() + kSampleLayoutHeaderBytes,
                    out.entries.size() * kSampleLayoutEntryBytes);
    return out;
}

uint32_t sampleFractionThreshold(float fraction) {
    if (!(fraction > 0.0f)) return 0u;  // also NaN: select nothing
    if (fraction >= 1.0f) return 0xFFFFFFFFu;
    return uint32_t(double(fraction) * 4294967296.0);  // < 2^32 since fraction < 1
}

uint32_t sampleListHash(uint32_t pixelIndex, uint32_t seed) {
    return hashCombine(seed, pixelIndex);
}

uint32_t sampleListSeed(uint64_t graphSeed, uint64_t frameIndex, bool animate) {
    uint32_t s = hashCombine(uint32_t(graphSeed), uint32_t(graphSeed >> 32));
    return animate ? hashCombine(s, uint32_t(frameIndex)) : s;
}

bool samplePatternSelects(const SamplePatternOptions& o, uint32_t x, uint32_t y, uint32_t width) {
    uint32_t index = y * width + x;
    switch (o.pattern) {
        case SamplePattern::All:
            return true;
        case SamplePattern::Checkerboard:
            return ((x + y) & 1u) == 0u;
        case SamplePattern::EveryNth:
            return index % std::max(o.n, 1u) == 0u;
        case SamplePattern::Random: {
            uint32_t t = sampleFractionThreshold(o.fraction);
            return t == 0xFFFFFFFFu || sampleListHash(index, o.seed) < t;
        }
    }
    return false;
}

SampleLayout buildSampleLayout(const SamplePatternOptions& o, uint32_t width, uint32_t height) {
    SampleLayout out;
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            if (samplePatternSelects(o, x, y, width)) out.add(x, y, o.samples);
    return out;
}

std::vector<std::string> validateSampleLayout(const SampleLayout& layout, uint32_t width,
                                              uint32_t height) {
    std::vector<std::string> issues;
    std::unordered_set<uint32_t> seen;
    for (size_t i = 0; i < layout.entries.size(); ++i) {
        const auto& e = layout.entries[i];
        glm::uvec2 p = unpackSamplePixel(e.pixel);
        std::string where = "entry " + std::to_string(i) + " (" + std::to_string(p.x) + ", " +
                            std::to_string(p.y) + ")";
        if (p.x >= width || p.y >= height)
            issues.push_back(where + ": outside the " + std::to_string(width) + "x" +
                             std::to_string(height) + " image");
        if (e.samples == 0) issues.push_back(where + ": sample count 0");
        if (!seen.insert(e.pixel).second) issues.push_back(where + ": pixel listed twice");
    }
    return issues;
}

void checkSampleLayoutSize(uint32_t width, uint32_t height) {
    if (width > kSampleLayoutMaxCoordinate + 1 || height > kSampleLayoutMaxCoordinate + 1)
        throw InputError("sample layouts store 16-bit coordinates; the render size is " +
                         std::to_string(width) + "x" + std::to_string(height));
}

}  // namespace fovea::sampling
