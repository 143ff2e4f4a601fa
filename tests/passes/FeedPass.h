// Test-only source pass "Feed": declares persistent outputs that a test fills from the host
// before a frame (the pass itself records nothing), so a pass under test can be fed exact inputs.
// feedRegistry() makes a registry holding Feed and the one pass type under test.
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/Pass.h"
#include "core/graph/PassRegistry.h"
#include "core/graph/RenderGraph.h"
#include "core/vk/Resources.h"

namespace fovea::test {

struct FeedField {
    std::string name;
    vk::Format format;
};

class FeedPass : public graph::Pass {
public:
    explicit FeedPass(std::vector<FeedField> fields) : mFields(std::move(fields)) {}
    void reflect(graph::Reflection& r) const override {
        for (const auto& f : mFields) r.output(f.name, f.format).persistent();
    }
    void execute(graph::ExecuteContext&) override {}

private:
    std::vector<FeedField> mFields;
};

// "Feed" with `fields` plus `type` created as T.
template <class T>
graph::PassRegistry feedRegistry(const std::string& type, std::vector<FeedField> fields) {
    graph::PassRegistry reg;
    reg.add({"Feed", "", [fields] { return std::make_unique<FeedPass>(fields); }});
    reg.add({type, "", [] { return std::make_unique<T>(); }});
    return reg;
}

// Builds Feed ("feed") -> `type` ("<pass>") at width x height: one edge feed.<f> -> <pass>.<f> per
// name in `connect`, the pass's `params` (JSON object text), `outputs` (field names) marked.
inline std::unique_ptr<graph::RenderGraph> buildFeedGraph(
    gpu::Context& ctx, const graph::PassRegistry& registry, const std::string& type,
    const std::string& pass, const std::string& params, const std::vector<std::string>& connect,
    const std::vector<std::string>& outputs, int width, int height) {
    std::string edges, marked;
    for (const auto& f : connect)
        edges += std::string(edges.empty() ? "" : ", ") + R"({ "from": "feed.)" + f +
                 R"(", "to": ")" + pass + "." + f + R"(" })";
    for (const auto& f : outputs)
        marked += std::string(marked.empty() ? "" : ", ") + "\"" + pass + "." + f + "\"";
    const std::string text = R"({ "version": 1, "name": ")" + pass +
                             R"(_test", "passes": [ { "name": "feed", "type": "Feed" }, )"
                             R"({ "name": ")" +
                             pass + R"(", "type": ")" + type + R"(", "params": )" + params +
                             R"( } ], "edges": [ )" + edges + R"( ], "outputs": [ )" + marked +
                             " ] }";
    graph::CompileOptions o;
    o.width = uint32_t(width);
    o.height = uint32_t(height);
    auto g = std::make_unique<graph::RenderGraph>(ctx, registry);
    g->build(graph::parseGraphText(text, pass + "_test"), o);
    return g;
}

// Feed never writes its (persistent) outputs, so the test owns their content.
inline void uploadFeed(gpu::Context& ctx, graph::RenderGraph& g, const std::string& field,
                       const std::vector<float>& rgba) {
    const_cast<gpu::Image&>(g.image("feed." + field)).uploadRGBA32F(ctx, rgba);
}

}  // namespace fovea::test
