#include "tests/graph/SvgfTestUtil.h"

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

void SvgfInputs::resize(int w, int h) {
    width = w;
    height = h;
    const size_t n = size_t(w) * size_t(h) * 4;
    for (auto* v : {&color, &position, &normal, &depth, &albedo, &emission, &motion})
        v->assign(n, 0.0f);
}

SvgfHarness::SvgfHarness(gpu::Context& ctx, const SvgfInputs& in, const std::string& params,
                         SvgfEdges edges)
    : mCtx(ctx) {
    std::string e = R"({ "from": "feed.color", "to": "svgf.color" },
                       { "from": "feed.position", "to": "svgf.position" },
                       { "from": "feed.normal", "to": "svgf.normal" },
                       { "from": "feed.depth", "to": "svgf.depth" })";
    if (edges.albedo) e += R"(, { "from": "feed.albedo", "to": "svgf.albedo" })";
    if (edges.emission) e += R"(, { "from": "feed.emission", "to": "svgf.emission" })";
    if (edges.motion) e += R"(, { "from": "feed.motion", "to": "svgf.motion" })";
    const std::string text =
        R"({ "version": 1, "name": "svgf_test", "passes": [ { "name": "feed", "type": "Feed" },)"
        R"( { "name": "svgf", "type": "SVGF", "params": )" +
        params + R"( } ], "edges": [ )" + e +
        R"( ], "outputs": [ "svgf.filtered", "svgf.illumination", "svgf.accumulated", )"
        R"("svgf.stats" ] })";
    CompileOptions o;
    o.width = uint32_t(in.width);
    o.height = uint32_t(in.height);
    mGraph = std::make_unique<RenderGraph>(ctx, registry());
    mGraph->build(parseGraphText(text, "svgf_test"), o);
    mGraph->setSeed(7);
    upload(in);
}

SvgfHarness::~SvgfHarness() = default;

void SvgfHarness::upload(const SvgfInputs& in, bool colorOnly) {
    // Feed never writes its (persistent) outputs, so the test owns their content.
    auto target = [&](const char* name) -> gpu::Image& {
        return const_cast<gpu::Image&>(mGraph->image(name));
    };
    target("feed.color").uploadRGBA32F(mCtx, in.color);
    if (colorOnly) return;
    target("feed.position").uploadRGBA32F(mCtx, in.position);
    target("feed.normal").uploadRGBA32F(mCtx, in.normal);
    target("feed.depth").uploadRGBA32F(mCtx, in.depth);
    target("feed.albedo").uploadRGBA32F(mCtx, in.albedo);
    target("feed.emission").uploadRGBA32F(mCtx, in.emission);
    target("feed.motion").uploadRGBA32F(mCtx, in.motion);
}

void SvgfHarness::runFrame() {
    mGraph->runFrame();
}

std::vector<float> SvgfHarness::read(const std::string& field) const {
    return mGraph->image("svgf." + field).downloadRGBA32F(mCtx);
}

std::vector<float> SvgfHarness::readFeed(const std::string& field) const {
    return mGraph->image("feed." + field).downloadRGBA32F(mCtx);
}

std::vector<uint32_t> SvgfHarness::stats() const {
    const auto& nodes = mGraph->plan().nodes;
    for (size_t i = 0; i < nodes.size(); ++i)
        if (nodes[i].name == "svgf")
            return mGraph->bufferFor(i, "stats").downloadAs<uint32_t>(mCtx);
    throw std::logic_error("no svgf pass");
}

SvgfInputs randomScene(int w, int h, uint32_t seed) {
    SvgfInputs in;
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

void recolor(SvgfInputs& in, uint32_t seed) {
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
