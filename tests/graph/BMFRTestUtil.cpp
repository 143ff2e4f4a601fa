#include "tests/graph/BMFRTestUtil.h"

#include <cmath>
#include <stdexcept>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/vk/Resources.h"
#include "tests/passes/FeedPass.h"

namespace fovea::testbmfr {

namespace {

using namespace fovea::graph;

const PassRegistry& registry() {
    // Formats as GBuffer / PathTrace produce them.
    static PassRegistry r =
        test::feedRegistry<passes::BMFRPass>("BMFR", {{"color", vk::Format::eR32G32B32A32Sfloat},
                                                      {"position", vk::Format::eR32G32B32A32Sfloat},
                                                      {"normal", vk::Format::eR16G16B16A16Sfloat},
                                                      {"albedo", vk::Format::eR16G16B16A16Sfloat},
                                                      {"emission", vk::Format::eR16G16B16A16Sfloat},
                                                      {"motion", vk::Format::eR16G16Sfloat}});
    return r;
}

}  // namespace

void BMFRInputs::resize(int w, int h) {
    width = w;
    height = h;
    const size_t n = size_t(w) * size_t(h) * 4;
    for (auto* v : {&color, &position, &normal, &albedo, &emission, &motion}) v->assign(n, 0.0f);
}

BMFRHarness::BMFRHarness(gpu::Context& ctx, const BMFRInputs& in, const std::string& params,
                         BMFREdges edges)
    : mCtx(ctx), mEdges(edges) {
    std::vector<std::string> connect = {"color", "position", "normal"};
    if (edges.albedo) connect.push_back("albedo");
    if (edges.emission) connect.push_back("emission");
    if (edges.motion) connect.push_back("motion");
    mGraph =
        test::buildFeedGraph(ctx, registry(), "BMFR", "bmfr", params, connect,
                             {"filtered", "accumulated", "fitted", "stats"}, in.width, in.height);
    mGraph->setSeed(7);
    upload(in);
}

BMFRHarness::~BMFRHarness() = default;

void BMFRHarness::upload(const BMFRInputs& in, bool colorOnly) {
    test::uploadFeed(mCtx, *mGraph, "color", in.color);
    if (colorOnly) return;
    test::uploadFeed(mCtx, *mGraph, "position", in.position);
    test::uploadFeed(mCtx, *mGraph, "normal", in.normal);
    test::uploadFeed(mCtx, *mGraph, "albedo", in.albedo);
    test::uploadFeed(mCtx, *mGraph, "emission", in.emission);
    test::uploadFeed(mCtx, *mGraph, "motion", in.motion);
}

void BMFRHarness::runFrame() {
    mGraph->runFrame();
}

std::vector<float> BMFRHarness::read(const std::string& field) const {
    return mGraph->image("bmfr." + field).downloadRGBA32F(mCtx);
}

std::vector<float> BMFRHarness::normalsUsed() const {
    return mGraph->image("feed.normal").downloadRGBA32F(mCtx);
}

passes::BMFRPass& BMFRHarness::pass() {
    for (auto& node : mGraph->plan().nodes)
        if (node.name == "bmfr") return dynamic_cast<passes::BMFRPass&>(*node.pass);
    throw std::logic_error("no bmfr pass");
}

std::vector<uint32_t> BMFRHarness::stats() const {
    const auto& nodes = mGraph->plan().nodes;
    for (size_t i = 0; i < nodes.size(); ++i)
        if (nodes[i].name == "bmfr")
            return mGraph->bufferFor(i, "stats").downloadAs<uint32_t>(mCtx);
    throw std::logic_error("no bmfr pass");
}

bool allFinite(const std::vector<float>& v) {
    for (float x : v)
        if (!std::isfinite(x)) return false;
    return true;
}

}  // namespace fovea::testbmfr
