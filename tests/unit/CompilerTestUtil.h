// Helpers of the compile-stage tests (Compiler*Tests.cpp): the test pass registry, compiling
// inline graph text, and views of a plan (order, culled passes, resources, alias groups,
// barriers). CPU only.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "core/graph/CompilerStages.h"
#include "core/graph/GraphDesc.h"
#include "core/util/Error.h"
#include "tests/passes/TestPasses.h"

namespace fovea::compilertest {

using namespace fovea::graph;
using fovea::testpasses::kRgba32fBytes;


inline const PassRegistry& registry() {
    static const PassRegistry r = testpasses::testRegistry();
    return r;
}

inline CompileOptions options64(bool aliasing = true) {
    CompileOptions o;
    o.width = 64;
    o.height = 64;
    o.aliasing = aliasing;
    return o;
}

inline CompiledPlan compile(const std::string& text, const CompileOptions& o = options64()) {
    return compileGraphPlan(parseGraphText(text, "test.json"), registry(), o);
}

// The message of the InputError compiling `text` throws, or "<no error>".
inline std::string compileError(const std::string& text, const CompileOptions& o = options64()) {
    try {
        compile(text, o);
    } catch (const InputError& e) {
        return e.what();
    }
    return "<no error>";
}

inline std::vector<std::string> orderNames(const CompiledPlan& plan) {
    std::vector<std::string> out;
    for (size_t n : plan.order) out.push_back(plan.nodes[n].name);
    return out;
}

inline std::vector<std::string> aliveNames(const CompiledPlan& plan) {
    std::vector<std::string> out;
    for (const auto& node : plan.nodes)
        if (node.alive) out.push_back(node.name);
    return out;
}

// Culled pass name -> reason.
inline std::map<std::string, std::string> culled(const CompiledPlan& plan) {
    std::map<std::string, std::string> out;
    for (const auto& node : plan.nodes)
        if (!node.alive) out[node.name] = node.cullReason;
    return out;
}

inline const ResourcePlan& resource(const CompiledPlan& plan, const std::string& name) {
    for (const auto& r : plan.resources)
        if (r.name == name) return r;
    ADD_FAILURE() << "no resource " << name;
    static const ResourcePlan none;
    return none;
}

inline bool hasResource(const CompiledPlan& plan, const std::string& name) {
    for (const auto& r : plan.resources)
        if (r.name == name) return true;
    return false;
}

inline std::vector<std::vector<std::string>> groupNames(const CompiledPlan& plan) {
    std::vector<std::vector<std::string>> out;
    for (const auto& g : plan.aliasGroups) {
        out.emplace_back();
        for (size_t m : g.members) out.back().push_back(plan.resources[m].name);
    }
    return out;
}

struct BarrierView {
    int position;
    std::vector<std::string> initialize;
    std::vector<std::string> hazards;
    bool operator==(const BarrierView&) const = default;
};

inline std::ostream& operator<<(std::ostream& s, const BarrierView& b) {
    s << "{pos " << b.position << ", init [";
    for (const auto& i : b.initialize) s << i << " ";
    s << "], hazards [";
    for (const auto& h : b.hazards) s << "'" << h << "' ";
    return s << "]}";
}

inline std::vector<BarrierView> barriers(const CompiledPlan& plan) {
    std::vector<BarrierView> out;
    for (const auto& b : plan.barriers) {
        BarrierView v{b.position, {}, b.hazards};
        for (size_t r : b.initialize) v.initialize.push_back(plan.resources[r].name);
        out.push_back(v);
    }
    return out;
}

inline constexpr uint64_t kImage64 = 64ull * 64 * kRgba32fBytes;

// src -> f1 -> f2 -> f3 -> f4, output f4.out.
inline constexpr const char* kChain = R"({ "version": 1,
  "passes": [ { "name": "src", "type": "Src" }, { "name": "f1", "type": "Filter" },
              { "name": "f2", "type": "Filter" }, { "name": "f3", "type": "Filter" },
              { "name": "f4", "type": "Filter" } ],
  "edges": [ { "from": "src.color", "to": "f1.in" }, { "from": "f1.out", "to": "f2.in" },
             { "from": "f2.out", "to": "f3.in" }, { "from": "f3.out", "to": "f4.in" } ],
  "outputs": [ "f4.out" ] })";

// src -> a, src -> b, (a, b) -> join.
inline constexpr const char* kDiamond = R"({ "version": 1,
  "passes": [ { "name": "src", "type": "Src" }, { "name": "a", "type": "Filter" },
              { "name": "b", "type": "Filter" }, { "name": "join", "type": "Join" } ],
  "edges": [ { "from": "src.color", "to": "a.in" }, { "from": "src.color", "to": "b.in" },
             { "from": "a.out", "to": "join.a" }, { "from": "b.out", "to": "join.b" } ],
  "outputs": [ "join.out" ] })";

using Names = std::vector<std::string>;
using Reasons = std::map<std::string, std::string>;


// src -> j, j.out -> j.b through a delayed edge of `delay` frames.
inline constexpr const char* kSelfLoop = R"({ "version": 1,
  "passes": [ { "name": "src", "type": "Src" }, { "name": "j", "type": "Join" } ],
  "edges": [ { "from": "src.color", "to": "j.a" }, { "from": "j.out", "to": "j.b", "delay": %s } ],
  "outputs": [ "j.out" ] })";

inline std::string selfLoop(const char* delay) {
    std::string text = kSelfLoop;
    text.replace(text.find("%s"), 2, delay);
    return text;
}

}  // namespace fovea::compilertest
