// Test-only source pass "Feed": declares persistent outputs that a test fills from the host
// before a frame (the pass itself records nothing), so a pass under test can be fed exact inputs.
// feedRegistry() makes a registry holding Feed and the one pass type under test.
#pragma once
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/graph/Pass.h"
#include "core/graph/PassRegistry.h"

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

}  // namespace fovea::test
