// Test rig of the ReBLUR passes (RecurrentBlur temporal + spatial, optional HistoryFix): a Feed
// pass provides PathTrace- and GBuffer-like inputs from the host; the graph is the three-node
// layout of graphs/reblur.json with the recurrence as a delay-1 edge. Scenes are planes facing
// the default camera (origin, looking down -z, yfov 0.8), so view depth, position, normal and the
// frustum size agree with each other.
#pragma once
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/vk/Resources.h"
#include "passes/HistoryFix/HistoryFixPass.h"
#include "passes/RecurrentBlur/RecurrentBlurSpatialPass.h"
#include "passes/RecurrentBlur/RecurrentBlurTemporalPass.h"
#include "tests/passes/FeedPass.h"

namespace fovea::test {

using Image = std::vector<float>;  // rgba32f, row-major

inline const graph::PassRegistry& reblurRegistry() {
    static graph::PassRegistry reg = [] {
        graph::PassRegistry r;
        const std::vector<FeedField> fields = {{"radiance", vk::Format::eR32G32B32A32Sfloat},
                                               {"hit_distance", vk::Format::eR32Sfloat},
                                               {"normal", vk::Format::eR16G16B16A16Sfloat},
                                               {"position", vk::Format::eR32G32B32A32Sfloat},
                                               {"depth", vk::Format::eR32Sfloat},
                                               {"motion", vk::Format::eR16G16Sfloat},
                                               {"roughness", vk::Format::eR16G16Sfloat},
                                               {"color", vk::Format::eR32G32B32A32Sfloat},
                                               {"albedo", vk::Format::eR32G32B32A32Sfloat},
                                               {"emission", vk::Format::eR32G32B32A32Sfloat}};
        r.add({"Feed", "", [fields] { return std::make_unique<FeedPass>(fields); }});
        r.add({"RecurrentBlurTemporal", "",
               [] { return std::make_unique<passes::RecurrentBlurTemporalPass>(); }});
        r.add({"RecurrentBlurSpatial", "",
               [] { return std::make_unique<passes::RecurrentBlurSpatialPass>(); }});
        r.add({"HistoryFix", "", [] { return std::make_unique<passes::HistoryFixPass>(); }});
        return r;
    }();
    return reg;
}

constexpr float kTanHalfFov = 0.42279322f;  // tan(0.8 / 2), FrameCamera's default yfov

// Per-pixel geometry; depth 0 = sky.
struct Geometry {
    Image normal, position, depth;
};

// Planes facing the camera: depth per pixel (0 = sky), lateral positions on the view frustum.
inline Geometry facingPlanes(int w, int h, const std::vector<float>& depthPerPixel) {
    Geometry g;
    g.normal.assign(size_t(w) * h * 4, 0.0f);
    g.position.assign(size_t(w) * h * 4, 0.0f);
    g.depth.assign(size_t(w) * h * 4, 0.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * w + x;
            const float z = depthPerPixel[i];
            if (!(z > 0.0f)) continue;
            const float pitch = 2.0f * kTanHalfFov * z / float(h);
            float* p = &g.position[i * 4];
            p[0] = (float(x) + 0.5f - 0.5f * float(w)) * pitch;
            p[1] = (0.5f * float(h) - float(y) - 0.5f) * pitch;
            p[2] = -z;
            p[3] = 1.0f;
            g.normal[i * 4 + 2] = 1.0f;
            g.normal[i * 4 + 3] = 1.0f;
            g.depth[i * 4] = z;
        }
    return g;
}

// Uniform [0, 1) noise in rgb, a = 1, reproducible from `seed`.
inline Image noise(int w, int h, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    Image img(size_t(w) * h * 4);
    for (size_t i = 0; i < img.size(); ++i) img[i] = i % 4 == 3 ? 1.0f : u(rng);
    return img;
}

inline Geometry facingPlane(int w, int h, float z) {
    return facingPlanes(w, h, std::vector<float>(size_t(w) * h, z));
}

inline Image constantImage(int w, int h, float r, float g, float b, float a = 1.0f) {
    Image img(size_t(w) * h * 4);
    for (size_t i = 0; i < img.size(); i += 4) {
        img[i] = r;
        img[i + 1] = g;
        img[i + 2] = b;
        img[i + 3] = a;
    }
    return img;
}

// Feed -> rbt (temporal) [-> hf (HistoryFix)] -> rbs (spatial), rbs.history -> rbt.history delay 1.
class ReblurRig {
public:
    ReblurRig(gpu::Context& gpu, int w, int h, const std::string& temporalParams,
              const std::string& spatialParams, bool historyFix = false,
              const std::string& fixParams = "{}")
        : mGpu(gpu), mGraph(gpu, reblurRegistry()), mW(w), mH(h) {
        std::string edges;
        // signal = specular (issue 26) also reads roughness (setRoughness), HistoryFix too.
        const bool specular = temporalParams.find("specular") != std::string::npos;
        for (const char* f : {"normal", "position", "depth", "motion", "roughness"}) {
            if (std::string(f) == "roughness" && !specular) continue;
            edges += std::string(R"({ "from": "feed.)") + f + R"(", "to": "rbt.)" + f + R"(" }, )";
            edges += std::string(R"({ "from": "feed.)") + f + R"(", "to": "rbs.)" + f + R"(" }, )";
        }
        if (specular && historyFix)
            edges += R"({ "from": "feed.roughness", "to": "hf.roughness" }, )";
        edges += R"({ "from": "feed.radiance", "to": "rbt.radiance" },
                    { "from": "feed.hit_distance", "to": "rbt.hit_distance" },
                    { "from": "rbt.hit", "to": "rbs.hit" },
                    { "from": "rbs.history", "to": "rbt.history", "delay": 1 }, )";
        std::string passes =
            R"({ "name": "feed", "type": "Feed" },
               { "name": "rbt", "type": "RecurrentBlurTemporal", "params": )" +
            pixelSizes(temporalParams) + R"( },
               { "name": "rbs", "type": "RecurrentBlurSpatial", "params": )" +
            pixelSizes(spatialParams) + " }";
        std::string outputs =
            R"("rbt.preblurred", "rbt.accumulated", "rbt.hit", "rbt.radius", "rbs.blurred", )"
            R"("rbs.history", "rbs.result", "rbs.radius")";
        if (historyFix) {
            passes += R"(, { "name": "hf", "type": "HistoryFix", "params": )" +
                      pixelSizes(fixParams) + " }";
            edges += R"({ "from": "rbt.accumulated", "to": "hf.color" },
                        { "from": "feed.depth", "to": "hf.depth" },
                        { "from": "hf.result", "to": "rbs.color" })";
            outputs += R"(, "hf.result")";
        } else {
            edges += R"({ "from": "rbt.accumulated", "to": "rbs.color" })";
        }
        const std::string text = R"({ "version": 1, "name": "reblur_test", "passes": [ )" + passes +
                                 R"( ], "edges": [ )" + edges + R"( ], "outputs": [ )" + outputs +
                                 " ] }";
        graph::CompileOptions o;
        o.width = uint32_t(w);
        o.height = uint32_t(h);
        mGraph.build(graph::parseGraphText(text, "reblur_test"), o);
    }

    void setGeometry(const Geometry& g) {
        target("feed.normal").uploadRGBA32F(mGpu, g.normal);
        target("feed.position").uploadRGBA32F(mGpu, g.position);
        target("feed.depth").uploadRGBA32F(mGpu, g.depth);
    }
    void setMotion(const Image& m) { target("feed.motion").uploadRGBA32F(mGpu, m); }
    // Linear roughness everywhere (signal = specular).
    void setRoughness(float r) {
        Image img(size_t(mW) * mH * 4, 0.0f);
        for (size_t i = 0; i < img.size(); i += 4) img[i] = r;
        target("feed.roughness").uploadRGBA32F(mGpu, img);
    }
    // hit: one float per pixel (0 = no indirect hit).
    void frame(const Image& radiance, const std::vector<float>& hit) {
        target("feed.radiance").uploadRGBA32F(mGpu, radiance);
        Image h(size_t(mW) * mH * 4, 0.0f);
        for (size_t i = 0; i < hit.size(); ++i) h[i * 4] = hit[i];
        target("feed.hit_distance").uploadRGBA32F(mGpu, h);
        mGraph.runFrame();
    }
    void frame(const Image& radiance) {
        frame(radiance, std::vector<float>(size_t(mW) * mH, 0.0f));
    }
    Image get(const std::string& output) { return mGraph.image(output).downloadRGBA32F(mGpu); }
    // Overwrites an output's current image (e.g. with NaN before the first frame).
    void poison(const std::string& output, float value) {
        target(output).uploadRGBA32F(mGpu, Image(size_t(mW) * mH * 4, value));
    }
    graph::RenderGraph& graph() { return mGraph; }
    void init() {  // zero motion, so an unset motion image is never read as garbage
        setMotion(Image(size_t(mW) * mH * 4, 0.0f));
    }

private:
    static std::string withKey(std::string params, const std::string& key) {
        const bool empty = params.find_first_not_of(" {}") == std::string::npos;
        if (empty) return "{" + key + " }";
        return params.insert(params.find('{') + 1, key + ",");
    }

public:
    // The tests' images are 8-64 px: radii, levels and strides are given in pixels
    // (referenceHeight 0) unless a test sets a reference height itself.
    static std::string pixelSizes(const std::string& params) {
        if (params.find("referenceHeight") != std::string::npos) return params;
        return withKey(params, R"( "referenceHeight": 0)");
    }

private:
    gpu::Image& target(const std::string& name) {
        return const_cast<gpu::Image&>(mGraph.image(name));
    }
    gpu::Context& mGpu;
    graph::RenderGraph mGraph;
    int mW, mH;
};

}  // namespace fovea::test
