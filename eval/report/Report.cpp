#include "eval/report/Report.h"

#include <algorithm>

#include "core/graph/PassRegistry.h"

namespace fovea::eval {

Stats computeStats(std::vector<double> values) {
    Stats s;
    if (values.empty()) return s;
    std::sort(values.begin(), values.end());
    double sum = 0;
    for (double v : values) sum += v;
    s.mean = sum / double(values.size());  // size >= 1 here
    size_t mid = values.size() / 2;
    s.median = values.size() % 2 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
    s.min = values.front();
    s.max = values.back();
    return s;
}

nlohmann::json statsJson(const Stats& s) {
    return {{"mean", s.mean}, {"median", s.median}, {"min", s.min}, {"max", s.max}};
}

nlohmann::json buildReport(const graph::RenderGraph& graph, const ReportInputs& in) {
    using nlohmann::json;
    const auto& plan = graph.plan();
    json passes = json::array();
    for (size_t n = 0; n < plan.nodes.size(); ++n) {
        const auto& node = plan.nodes[n];
        const auto& rec = graph.records()[n];
        json p = {{"name", node.name},
                  {"type", node.type},
                  {"status", graph::passStatusName(rec.status)},
                  {"reason", rec.reason},
                  {"executions", rec.executions},
                  // Memory the pass allocated itself, invisible to the plan (contract: 0).
                  {"allocations_outside_plan", rec.allocationsOutsidePlan},
                  // Dispatches since the build, and the barriers the graph derived between them.
                  {"dispatches", rec.dispatches},
                  {"barriers_in_pass", rec.barriersInPass},
                  {"gpu_ms", statsJson(computeStats(rec.gpuMs))}};
        // With --profile-dispatches: the pass's time split by dispatch.
        if (!rec.dispatchMs.empty()) {
            json split = json::array();
            for (const auto& d : rec.dispatchMs)
                split.push_back({{"shader", d.shader},
                                 {"occurrence", d.occurrence},
                                 {"runs", d.ms.size()},
                                 {"ms", statsJson(computeStats(d.ms))}});
            p["dispatch_gpu_ms"] = split;
        }
        // Which shader specialization ran (scene features, BRDF, ...), for passes that have one.
        if (node.pass) {
            std::string variant = node.pass->variant();
            if (!variant.empty()) p["variant"] = variant;
            // Counters the pass keeps (e.g. BMFR's sanitized NaN inputs), after the last frame.
            json statistics = graph.passStatistics(n);
            if (!statistics.is_null()) p["statistics"] = statistics;
        }
        // A type from a pass plugin names its library (docs/plugins.md).
        // (fovea runs graphs on the global registry: eval/run/GraphRunner.cpp.)
        if (std::string origin = graph::passRegistry().origin(node.type); !origin.empty())
            p["plugin"] = origin;
        passes.push_back(p);
    }
    nlohmann::json report = {
        {"report_version", kReportSchemaVersion},
        {"fovea_version", FOVEA_VERSION},
        {"graph", in.graphFile},
        {"scene", in.scene},
        {"device", {{"name", in.deviceName}, {"driver", in.driver}}},
        {"shader_dir", in.shaderDir},
        {"size", {in.width, in.height}},
        {"frames", in.frames},
        {"seed", in.seed},
        {"build_ms", in.buildMs},
        {"passes", passes},
        {"memory",
         {{"transient_bytes", plan.transientBytes()},
          {"transient_bytes_without_aliasing", plan.transientBytesWithoutAliasing()},
          {"persistent_bytes", plan.persistentBytes()},
          {"history_bytes", plan.historyBytes()},
          {"allocated_transient_bytes", graph.allocatedTransientBytes()},
          {"allocated_persistent_bytes", graph.allocatedPersistentBytes()}}},
        {"frame_ms", statsJson(computeStats(in.frameGpuMs))},
        {"frame_cpu_ms", statsJson(computeStats(in.frameCpuMs))},
        {"executor_overhead_cpu_ms", statsJson(computeStats(in.overheadCpuMs))},
        {"outputs", in.outputs}};
    if (!in.reference.is_null()) report["reference"] = in.reference;
    return report;
}

}  // namespace fovea::eval
