// The compile stages of a graph, each a plain function over CompiledPlan (no GPU), in the order
// compileGraphPlan() runs them. Errors are InputError naming the graph file and JSON pointer.
#pragma once
#include "core/graph/GraphPlan.h"
#include "core/graph/PassRegistry.h"

namespace fovea::graph {

// 1. Creates one node per pass (unknown type: did-you-mean) and loads its parameters.
void instantiatePasses(const GraphDesc& desc, const PassRegistry& registry, CompiledPlan& plan);
// 2. Asks every pass for its fields.
void reflectPasses(CompiledPlan& plan);
// 3. Edges: fields exist, direction output -> input, formats and kinds agree, required inputs
//    connected, marked outputs are outputs, and no cycle unless it passes a delayed edge.
void checkEdges(const GraphDesc& desc, CompiledPlan& plan);
// 4. Culling with reasons: disabled, scene needs unmet, required input from a culled pass
//    (propagated), reaches no marked output.
void cullPasses(CompiledPlan& plan);
// 4b. Pass::validate on every alive pass: parameters against each other, the connected edges, the
//     render size and the scene (errors name /passes/i/params/<name>).
void validatePasses(CompiledPlan& plan);
// 5. Deterministic topological order of alive passes (ties: graph-file order).
void orderPasses(CompiledPlan& plan);
// 6. One resource per alive output/internal: size, format, lifetime class, ring size, first and
//    last use; input size rules are checked here.
void resolveResources(CompiledPlan& plan);
// 7. Transient images whose lifetimes do not overlap share memory (greedy interval colouring).
void aliasResources(CompiledPlan& plan);
// 8. Barriers between passes: read-after-write and aliasing hand-overs, with reasons.
void planBarriers(CompiledPlan& plan);

// Runs 1..8 (with 4b).
CompiledPlan compileGraphPlan(const GraphDesc& desc, const PassRegistry& registry,
                              const CompileOptions& options);

// Human-readable and JSON dumps (fovea validate --dump, tests, the inspector).
std::string dumpPlanText(const CompiledPlan& plan);
nlohmann::json dumpPlanJson(const CompiledPlan& plan);

}  // namespace fovea::graph
