// The tables of `fovea bench`: bench.json (everything), bench.csv (one row per graph) and
// bench.md (the summary and the per-pass breakdown), docs/bench.md.
#include <cmath>
#include <cstdio>
#include <sstream>

#include "apps/fovea/Bench.h"
#include "apps/fovea/OutputFolder.h"

namespace fovea::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string number(double v, const char* format = "%.4g") {
    if (std::isinf(v)) return "inf";  // PSNR of identical images
    char text[64];
    std::snprintf(text, sizeof text, format, v);
    return text;
}

// CSV field: quoted when it holds a comma, quote or newline (RFC 4180).
std::string csv(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

// Markdown table cell: a '|' would split the cell.
std::string md(const std::string& s) {
    std::string out;
    for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
}

json resultJson(const BenchResult& r) {
    json passes = json::array();
    for (const auto& p : r.passes)
        passes.push_back({{"name", p.name},
                          {"type", p.type},
                          {"status", p.status},
                          {"executions", p.executions},
                          {"gpu_ms", statsJson(p.gpuMs)}});
    return {{"label", r.graph.label},
            {"file", r.graph.file},
            {"set", r.graph.sets},
            {"output", r.output},
            {"frame_ms", statsJson(r.frameMs)},
            {"speedup", r.speedup},
            {"errors", r.errors},
            {"passes", passes}};
}

}  // namespace

namespace {

// The mean RMSE of the three eccentricity bands (FrameErrors' "bands"; NaN when absent).
std::vector<double> bandRmse(const BenchResult& r) {
    std::vector<double> out(3, std::nan(""));
    const json* bands = nullptr;
    if (r.errors.contains("mean") && r.errors["mean"].contains("bands"))
        bands = &r.errors["mean"]["bands"];
    for (size_t b = 0; bands && b < out.size() && b < bands->size(); ++b)
        out[b] = (*bands)[b].at("rmse").get<double>();
    return out;
}

}  // namespace

void writeBenchTables(const OutputFolder& folder, const json& header,
                      const std::vector<BenchResult>& results) {
    std::ostringstream c;
    c << "label,file,output,frame_ms_median,frame_ms_mean,speedup,rmse_percent,rmse,rel_mse,"
         "psnr_db,ssim,temporal_error,rmse_0_5deg,rmse_5_20deg,rmse_20deg_plus\n";
    for (const auto& r : results) {
        const auto& m = r.meanErrors;
        c << csv(r.graph.label) << "," << csv(r.graph.file) << "," << csv(r.output) << ","
          << number(r.frameMs.median, "%.6g") << "," << number(r.frameMs.mean, "%.6g") << ","
          << number(r.speedup, "%.6g") << "," << number(m.rmsePercent, "%.6g") << ","
          << number(m.rmse, "%.6g") << "," << number(m.relMse, "%.6g") << ","
          << number(m.psnr, "%.6g") << "," << number(m.ssim, "%.6g") << ","
          << number(r.temporalError, "%.6g");
        for (double v : bandRmse(r)) c << "," << number(v, "%.6g");
        c << "\n";
    }
    folder.writeText("bench.csv", c.str());

    std::ostringstream t;
    const json& size = header["size"];
    t << "# " << header["name"].get<std::string>() << "\n\n"
      << "Device: " << header["device"]["name"].get<std::string>() << " ("
      << header["device"]["driver"].get<std::string>() << "). Scene "
      << header["scene"].get<std::string>() << ", camera " << header["camera"].get<std::string>()
      << ", " << size[0].get<uint32_t>() << "x" << size[1].get<uint32_t>()
      << (header["stereo"].get<bool>() ? " stereo" : " mono") << ", "
      << header["frames"].get<uint32_t>() << " frames of which " << header["warmup"].get<uint32_t>()
      << " warm-up. Reference: " << header["reference"]["path"].get<std::string>()
      << ". Times are GPU medians over the "
      << "measured frames; errors are means over them; speedup is against the first graph ("
      << md(results.front().graph.label) << ") of the same run.\n\n"
      << "| Graph | Output | Frame ms (median) | Speedup | RMSE % | PSNR dB | SSIM | Temporal "
         "error "
         "|\n|---|---|---:|---:|---:|---:|---:|---:|\n";
    for (const auto& r : results) {
        const auto& m = r.meanErrors;
        t << "| " << md(r.graph.label) << " | " << md(r.output) << " | "
          << number(r.frameMs.median, "%.3f") << " | " << number(r.speedup, "%.2fx") << " | "
          << number(m.rmsePercent, "%.4f") << " | " << number(m.psnr, "%.2f") << " | "
          << number(m.ssim, "%.4f") << " | " << number(r.temporalError, "%.5f") << " |\n";
    }
    t << "\n## RMSE per eccentricity band (degrees from the gaze; mean over measured frames)\n\n"
      << "| Graph | 0-5 deg | 5-20 deg | 20+ deg |\n|---|---:|---:|---:|\n";
    for (const auto& r : results) {
        t << "| " << md(r.graph.label);
        for (double v : bandRmse(r)) t << " | " << number(v, "%.5f");
        t << " |\n";
    }
    t << "\n## GPU ms per pass (median over measured frames)\n\n"
      << "| Graph | Pass | Type | Median ms | Executions | Status (last frame) |\n"
      << "|---|---|---|---:|---:|---|\n";
    for (const auto& r : results)
        for (const auto& p : r.passes)
            t << "| " << md(r.graph.label) << " | " << md(p.name) << " | " << md(p.type) << " | "
              << number(p.gpuMs.median, "%.3f") << " | " << p.executions << " | " << p.status
              << " |\n";
    t << "\n![run time against error](bench.svg)\n";
    folder.writeText("bench.md", t.str());

    // Written last: its presence and "finished" say that the folder is complete (as report.json).
    json all = header;
    all["graphs"] = json::array();
    for (const auto& r : results) all["graphs"].push_back(resultJson(r));
    all["finished"] = true;
    folder.writeText("bench.json", all.dump(2) + "\n");
}

}  // namespace fovea::app
