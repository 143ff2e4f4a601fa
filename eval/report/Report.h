// report.json: the stable, documented record of a run (docs/report-format.md).
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/graph/RenderGraph.h"

namespace fovea::eval {

struct Stats {
    double mean = 0, median = 0, min = 0, max = 0;
};
Stats computeStats(std::vector<double> values);
nlohmann::json statsJson(const Stats& s);

struct ReportInputs {
    std::string graphFile, deviceName, driver;
    std::string shaderDir;  // the shader folder the run compiled from (core/util/InstallPaths.h)
    nlohmann::json scene = "none";  // "none" or RunScene::json()
    uint32_t width = 0, height = 0, frames = 0;
    uint64_t seed = 0;
    double buildMs = 0;  // RenderGraph::build: plan compile, allocation, pass compile (shaders)
    std::vector<double> frameGpuMs, frameCpuMs, overheadCpuMs;
    std::vector<std::string> outputs;  // written files, relative to the out dir
    nlohmann::json reference;          // null, or the "reference" object (run --reference)
};

constexpr int kReportSchemaVersion = 3;
nlohmann::json buildReport(const graph::RenderGraph& graph, const ReportInputs& in);

}  // namespace fovea::eval
