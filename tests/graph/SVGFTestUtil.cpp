#include "tests/graph/SVGFTestUtil.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/vk/Resources.h"
#include "passes/SVGF/SVGFPass.h"
#include "tests/passes/FeedPass.h"

namespace fovea::testsvgf {

namespace {

using namespace fovea::graph;

const PassRegistry& registry() {
    // Formats as GBuffer / PathTrace produce them.
    static PassRegistry r =
        test::feedRegistry<passes::SVGFPass>("SVGF", {{"color", vk::Format::eR32G32B32A32Sfloat},
                                                      {"position", vk::Format::eR32G32B32A32Sfloat},
                                                      {"normal", vk::Format::eR16G16B16A16Sfloat},
                                                      {"depth", vk::Format::eR32Sfloat},
                                                      {"albedo", vk::Format::eR16G16B16A16Sfloat},
                                                      {"emission", vk::Format::eR16G16B16A16Sfloat},
                                                      {"motion", vk::Format::eR16G16Sfloat}});
    return r;
}

}  // namespace

void SVGFInputs::resize(int w, int h) {
    width = w;
    height = h;
    const size_t n = size_t(w) * size_t(h) * 4;
    for (auto* v : {&color, &position, &normal, &depth, &albedo, &emission, &motion})
        v->assign(n, 0.0f);
}

SVGFHarness::SVGFHarness(gpu::Context& ctx, const SVGFInputs& in, const std::string& params,
                         SVGFEdges edges)
    : mCtx(ctx) {
    std::vector<std::string> connect = {"color", "position", "normal", "depth"};
    if (edges.albedo) connect.push_back("albedo");
    if (edges.emission) connect.push_back("emission");
    if (edges.motion) connect.push_back("motion");
    mGraph = test::buildFeedGraph(ctx, registry(), "SVGF", "svgf", params, connect,
                                  {"filtered", "illumination", "accumulated", "stats"}, in.width,
                                  in.height);
    mGraph->setSeed(7);
    upload(in);
}

SVGFHarness::~SVGFHarness() = default;

void SVGFHarness::upload(const SVGFInputs& in, bool colorOnly) {
    test::uploadFeed(mCtx, *mGraph, "color", in.color);
    if (colorOnly) return;
    test::uploadFeed(mCtx, *mGraph, "position", in.position);
    test::uploadFeed(mCtx, *mGraph, "normal", in.normal);
    test::uploadFeed(mCtx, *mGraph, "depth", in.depth);
    test::uploadFeed(mCtx, *mGraph, "albedo", in.albedo);
    test::uploadFeed(mCtx, *mGraph, "emission", in.emission);
    test::uploadFeed(mCtx, *mGraph, "motion", in.motion);
}

void SVGFHarness::runFrame() {
    mGraph->runFrame();
}

std::vector<float> SVGFHarness::read(const std::string& field) const {
    return mGraph->image("svgf." + field).downloadRGBA32F(mCtx);
}

std::vector<float> SVGFHarness::readFeed(const std::string& field) const {
    return mGraph->image("feed." + field).downloadRGBA32F(mCtx);
}

std::vector<uint32_t> SVGFHarness::stats() const {
    const auto& nodes = mGraph->plan().nodes;
    for (size_t i = 0; i < nodes.size(); ++i)
        if (nodes[i].name == "svgf")
            return mGraph->bufferFor(i, "stats").downloadAs<uint32_t>(mCtx);
    throw std::logic_error("no svgf pass");
}

SVGFInputs randomScene(int w, int h, uint32_t seed) {
    SVGFInputs in;
    in.resize(w, h);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = in.at(x, y);
            if ((x * 7 + y * 3) % 41 == 0) continue;  // a few misses: all zero
            // Left: a plane tilted along x; right: a nearer plane tilted along y (depth step).
            const bool right = x >= w / 2;
            const float z = right ? 3.0f + 0.02f * float(y) : 5.0f + 0.03f * float(x);
            const float fx = (float(x) + 0.5f) / float(w) - 0.5f;
            const float fy = (float(y) + 0.5f) / float(h) - 0.5f;
            in.depth[i] = z;
            in.position[i + 0] = fx * z;
            in.position[i + 1] = fy * z;
            in.position[i + 2] = -z;
            in.position[i + 3] = 1.0f;
            float n[3] = {right ? 0.1f : 0.3f, right ? 0.4f : 0.05f, 1.0f};
            n[0] += 0.2f * std::sin(0.4f * float(x)) * float(right);  // a bump
            n[1] += 0.2f * u(rng);
            const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int c = 0; c < 3; ++c) {
                in.normal[i + c] = n[c] / len;
                in.albedo[i + c] = 0.2f + 0.8f * u(rng);
                in.emission[i + c] = (x == 3 && y == 3) ? 2.0f : 0.0f;
            }
            in.normal[i + 3] = in.albedo[i + 3] = in.emission[i + 3] = 1.0f;
        }
    recolor(in, seed * 31u + 1u);
    return in;
}

void recolor(SVGFInputs& in, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int y = 0; y < in.height; ++y)
        for (int x = 0; x < in.width; ++x) {
            const size_t i = in.at(x, y);
            const float base = 0.5f + 0.4f * std::sin(0.2f * float(x)) * std::cos(0.1f * float(y));
            for (int c = 0; c < 3; ++c) in.color[i + c] = base * (0.5f + u(rng)) + 0.1f * float(c);
            in.color[i + 3] = 1.0f;
        }
}

bool allFinite(const std::vector<float>& v) {
    for (float x : v)
        if (!std::isfinite(x)) return false;
    return true;
}

}  // namespace fovea::testsvgf
