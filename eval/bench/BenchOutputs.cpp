// The tables of `fovea bench`: bench.json (everything), bench.csv (one row per graph) and
// bench.md (the summary and the per-pass breakdown), docs/bench.md.
#include <cmath>
#include <sstream>

#include "eval/bench/Bench.h"
#include "eval/metrics/ImageMetrics.h"
#include "eval/report/OutputFolder.h"

namespace fovea::eval {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// CSV field: quoted when it holds a comma, quote or newline (RFC 4180).
std::string csv(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

json resultJson(const BenchResult& r) {
    json against = json::object();
    for (const auto& a : r.against) against[a.label] = a.errors;
    json passes = json::array();
    for (const auto& p : r.passes)
        passes.push_back({{"name", p.name},
                          {"type", p.type},
                          {"status", p.status},
                          {"executions", p.executions},
                          {"gpu_ms", statsJson(p.gpuMs)}});
    json out = {{"label", r.graph.label},
                {"file", r.graph.file},
                {"set", r.graph.sets},
                {"output", r.output},
                {"frame_ms", statsJson(r.frameMs)},
                {"speedup", r.speedup},
                {"pareto", r.pareto},
                {"errors", r.errors},
                {"also_against", against},
                {"passes", passes}};
    if (!r.difference.is_null()) out["difference"] = r.difference;
    return out;
}

}  // namespace

namespace {

const char* const kBandFigures[] = {"rmse_0_5deg", "rmse_5_20deg", "rmse_20deg_plus"};
const char* const kLayerFigures[] = {"rmse_percent_fovea", "rmse_percent_middle",
                                     "rmse_percent_outer"};

// {markdown label, csv column} of each eccentricity band.
using BandColumns = std::vector<std::pair<std::string, std::string>>;

// The eccentricity bands the errors hold, from the first result's mean: {markdown label, csv
// column}. A perspective camera gives 0-5, 5-20, 20+ degrees (rmse_0_5deg, rmse_5_20deg,
// rmse_20deg_plus); an equirect one 0-5, 5-10, 10-20, 20-80, 80+ (EccentricityBands.h). Without
// any errors the perspective three, so the csv header keeps its columns.
BandColumns bandColumns(const std::vector<BenchResult>& results) {
    BandColumns out;
    const json* bands = nullptr;
    if (!results.empty() && results.front().errors.contains("mean") &&
        results.front().errors["mean"].contains("bands"))
        bands = &results.front().errors["mean"]["bands"];
    auto number = [](double v) { return benchNumber(v, "%g"); };
    if (bands && bands->is_array() && !bands->empty()) {
        for (const auto& b : *bands) {
            const std::string from = number(b.at("from").get<double>());
            if (b.at("to").is_null()) {
                out.push_back({from + "+ deg", "rmse_" + from + "deg_plus"});
            } else {
                const std::string to = number(b.at("to").get<double>());
                out.push_back({from + "-" + to + " deg", "rmse_" + from + "_" + to + "deg"});
            }
        }
        return out;
    }
    return {
        {"0-5 deg", kBandFigures[0]}, {"5-20 deg", kBandFigures[1]}, {"20+ deg", kBandFigures[2]}};
}

// The mean RMSE of each of `count` eccentricity bands (FrameErrors' "bands"; NaN when absent).
std::vector<double> bandRmse(const json& errors, size_t count) {
    std::vector<double> out(count, std::nan(""));
    if (!errors.contains("mean") || !errors["mean"].contains("bands")) return out;
    const json& bands = errors["mean"]["bands"];
    for (size_t b = 0; b < count && b < bands.size(); ++b)
        if (bands[b].contains("rmse") && bands[b]["rmse"].is_number())
            out[b] = bands[b]["rmse"].get<double>();
    return out;
}

// The mean RMSE % of the three foveation layers (FrameErrors' "layers"; NaN when absent).
std::vector<double> layerRmsePercent(const json& errors) {
    std::vector<double> out;
    for (const char* f : kLayerFigures) out.push_back(benchFigure(errors, f));
    return out;
}

double meanOf(const json& errors, const char* key) {
    if (!errors.contains("mean") || !errors["mean"].contains(key) ||
        !errors["mean"][key].is_number())
        return std::nan("");
    return errors["mean"][key].get<double>();
}

// The worst frame's number and RMSE % (NaN/none when absent).
std::pair<std::string, double> worstOf(const json& errors) {
    if (!errors.contains("worst")) return {"", std::nan("")};
    return {std::to_string(errors["worst"].at("frame").get<uint32_t>()),
            errors["worst"].at("rmse_percent").get<double>()};
}

// The noise floor (the second reference against the first) of reference `label`; null when none.
const json* floorOf(const json& header, const std::string& label) {
    if (!header.contains("noise_floor") || !header["noise_floor"].contains(label)) return nullptr;
    return &header["noise_floor"][label];
}

// RMSE % with the reference's own noise (half the floor's MSE) taken out (ImageMetrics.h
// noiseCorrectedRmse); NaN without a floor.
double correctedPercent(const json& errors, const json* floor) {
    if (!floor) return std::nan("");
    return 100.0 * eval::noiseCorrectedRmse(meanOf(errors, "mse"), meanOf(*floor, "mse"));
}

std::string layerHeading(const json& header) {
    if (!header.contains("layers")) return "";
    const json& l = header["layers"];
    const std::string unit = l.at("unit").get<std::string>() == "degrees" ? " deg" : " px";
    return "fovea (d <= " + benchNumber(l.at("r0").get<double>(), "%g") + unit +
           ") | middle (<= " + benchNumber(l.at("r1").get<double>(), "%g") + unit + ") | outer";
}

// The error table of one reference: per graph the mean RMSE %, the RMSE % corrected for the
// reference's noise, the worst frame, and the RMSE % per foveation layer; a first row holds the
// noise floor itself.
void errorTable(std::ostream& t, const json& header, const std::vector<BenchResult>& results,
                const std::string& label, const std::vector<const json*>& errors) {
    const json* floor = floorOf(header, label);
    const std::string layers = layerHeading(header);
    t << "| Graph | RMSE % | RMSE % above the reference noise | Worst frame | Worst RMSE %"
      << (layers.empty() ? "" : " | " + layers) << " |\n|---|---:|---:|---:|---:|"
      << (layers.empty() ? "" : "---:|---:|---:|") << "\n";
    auto row = [&](const std::string& name, const json& e, const json* fl) {
        const auto [worstFrame, worstPercent] = worstOf(e);
        // Several seeds: the worst frame of all seeds, and which seed it was.
        const std::string seed =
            e.contains("worst") && e["worst"].contains("seed")
                ? " (seed " + std::to_string(e["worst"]["seed"].get<uint64_t>()) + ")"
                : "";
        t << "| " << benchMarkdown(name) << " | " << benchNumber(meanOf(e, "rmse_percent"), "%.4f")
          << " | " << (fl ? benchNumber(correctedPercent(e, fl), "%.4f") : std::string("—"))
          << " | " << worstFrame << seed << " | " << benchNumber(worstPercent, "%.4f");
        if (!layers.empty())
            for (double v : layerRmsePercent(e)) t << " | " << benchNumber(v, "%.4f");
        t << " |\n";
    };
    if (floor) row("*noise floor: 2nd reference*", *floor, nullptr);
    for (size_t i = 0; i < results.size(); ++i) row(results[i].graph.label, *errors[i], floor);
}

// How to read the floor (docs/benchmarks.md, "the paper's protocol").
void floorNote(std::ostream& t, const json& header, const std::string& label) {
    const json* floor = floorOf(header, label);
    if (!floor) {
        t << "No noise floor for this reference (bench key `noise_floor`): errors close to the "
             "reference's own noise cannot be told from it.\n\n";
        return;
    }
    const double f = meanOf(*floor, "rmse_percent");
    t << "Noise floor: a second reference with another seed differs from this one by RMSE "
      << benchNumber(f, "%.4f") << " %, so the reference itself is about "
      << benchNumber(f / std::sqrt(2.0), "%.4f")
      << " % (floor / sqrt 2) from the truth. A graph's error against it is at least that; "
         "\"above the reference noise\" takes half the floor's MSE out (sqrt(MSE - floor MSE / "
         "2)), 0 = within the reference's noise. Differences between graphs smaller than the "
         "floor are not resolved.\n\n";
}

// Several seeds: every graph ran once per seed, and the errors hold the per-seed figures.
bool ranSeveralSeeds(const std::vector<BenchResult>& results) {
    return results.front().errors.contains("seeds");
}

void csvHeader(std::ostream& c, const std::vector<BenchResult>& results,
               const BandColumns& bandColumnList, bool seeds) {
    c << "label,file,output,frame_ms_median,frame_ms_mean,speedup,rmse_percent,rmse,rel_mse,"
         "psnr_db,ssim,temporal_error,flip_mean";
    for (const auto& column : bandColumnList) c << "," << column.second;
    c << ","
         "rmse_percent_noise_floor,rmse_percent_above_noise,worst_frame,worst_rmse_percent,"
         "rmse_percent_fovea,rmse_percent_middle,rmse_percent_outer,pareto";
    for (const auto& a : results.front().against)
        c << "," << csv("rmse_percent_" + a.label) << "," << csv("worst_rmse_percent_" + a.label);
    if (seeds) c << seedCsvHeader();
    c << "\n";
}

void csvRow(std::ostream& c, const BenchResult& r, const BandColumns& bandColumnList,
            const json* floor, bool seeds) {
    const auto& m = r.meanErrors;
    c << csv(r.graph.label) << "," << csv(r.graph.file) << "," << csv(r.output) << ","
      << benchNumber(r.frameMs.median, "%.6g") << "," << benchNumber(r.frameMs.mean, "%.6g") << ","
      << benchNumber(r.speedup, "%.6g") << "," << benchNumber(m.rmsePercent, "%.6g") << ","
      << benchNumber(m.rmse, "%.6g") << "," << benchNumber(m.relMse, "%.6g") << ","
      << benchNumber(m.psnr, "%.6g") << "," << benchNumber(m.ssim, "%.6g") << ","
      << benchNumber(r.temporalError, "%.6g") << "," << benchNumber(m.flipMean, "%.6g");
    for (double v : bandRmse(r.errors, bandColumnList.size())) c << "," << benchNumber(v, "%.6g");
    const auto [worstFrame, worstPercent] = worstOf(r.errors);
    c << "," << benchNumber(floor ? meanOf(*floor, "rmse_percent") : std::nan(""), "%.6g") << ","
      << benchNumber(correctedPercent(r.errors, floor), "%.6g") << "," << worstFrame << ","
      << benchNumber(worstPercent, "%.6g");
    for (double v : layerRmsePercent(r.errors)) c << "," << benchNumber(v, "%.6g");
    c << "," << (r.pareto ? "true" : "false");
    for (const auto& a : r.against)
        c << "," << benchNumber(a.meanErrors.rmsePercent, "%.6g") << ","
          << benchNumber(worstOf(a.errors).second, "%.6g");
    if (seeds) c << seedCsvRow(r);
    c << "\n";
}

// bench.csv: one row per graph.
std::string csvTable(const json& header, const std::vector<BenchResult>& results,
                     const BandColumns& bandColumnList) {
    std::ostringstream c;
    const json* floor = floorOf(header, "reference");
    const bool seeds = ranSeveralSeeds(results);
    csvHeader(c, results, bandColumnList, seeds);
    for (const auto& r : results) csvRow(c, r, bandColumnList, floor, seeds);
    return c.str();
}

// The title and the paragraph that says what was run and how the figures were measured.
void summaryParagraph(std::ostream& t, const json& header,
                      const std::vector<BenchResult>& results) {
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
      << benchMarkdown(results.front().graph.label) << ") of the same run.";
    if (ranSeveralSeeds(results)) {
        t << " Every graph ran once per seed (";
        const json& list = header.at("seeds");
        for (size_t i = 0; i < list.size(); ++i) t << (i ? ", " : "") << list[i];
        t << "): times are over the measured frames of all seeds, errors are the means over the "
             "seeds of each seed's mean, ± their standard error.";
    }
    t << "\n\n";
}

void summaryTable(std::ostream& t, const std::vector<BenchResult>& results) {
    t << "| Graph | Output | Frame ms (median) | Speedup | RMSE % | PSNR dB | SSIM | ꟻLIP | "
         "Temporal error | Pareto "
         "|\n|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (const auto& r : results) {
        const auto& m = r.meanErrors;
        t << "| " << benchMarkdown(r.graph.label) << " | " << benchMarkdown(r.output) << " | "
          << benchNumber(r.frameMs.median, "%.3f") << " | " << benchNumber(r.speedup, "%.2fx")
          << " | " << benchNumber(m.rmsePercent, "%.4f")
          << standardErrorSuffix(r.errors, "rmse_percent", "%.4f") << " | "
          << benchNumber(m.psnr, "%.2f") << " | " << benchNumber(m.ssim, "%.4f")
          << " | "
          // NaN = not measured (bench "flip": false): a dash, not "nan ± nan".
          << (std::isnan(m.flipMean) ? std::string("—")
                                     : benchNumber(m.flipMean, "%.4f") +
                                           standardErrorSuffix(r.errors, "flip_mean", "%.4f"))
          << " | " << benchNumber(r.temporalError, "%.5f") << " | " << (r.pareto ? "**yes**" : "")
          << " |\n";
    }
    t << "\nPareto: no other graph of this run is both faster (median frame ms) and closer to the "
         "reference (RMSE %); the front is marked in the plot.\n";
}

// One section per reference: the bench's own first, then each of `also_against`.
void errorSections(std::ostream& t, const json& header, const std::vector<BenchResult>& results) {
    t << "\n## Error against the reference: noise floor, worst frame, layers\n\n";
    floorNote(t, header, "reference");
    std::vector<const json*> primary;
    for (const auto& r : results) primary.push_back(&r.errors);
    errorTable(t, header, results, "reference", primary);
    for (size_t a = 0; a < results.front().against.size(); ++a) {
        const std::string label = results.front().against[a].label;
        t << "\n## Error against the reference '" << benchMarkdown(label) << "'";
        if (header.contains("also_against") && a < header["also_against"].size())
            t << " (" << header["also_against"][a].at("path").get<std::string>() << ")";
        t << "\n\n";
        floorNote(t, header, label);
        std::vector<const json*> errors;
        for (const auto& r : results) errors.push_back(&r.against[a].errors);
        errorTable(t, header, results, label, errors);
    }
}

void bandTable(std::ostream& t, const std::vector<BenchResult>& results,
               const BandColumns& bandColumnList) {
    t << "\n## RMSE per eccentricity band (degrees from the gaze; mean over measured frames)\n\n"
      << "| Graph |";
    for (const auto& column : bandColumnList) t << " " << column.first << " |";
    t << "\n|---|";
    for (size_t b = 0; b < bandColumnList.size(); ++b) t << "---:|";
    t << "\n";
    for (const auto& r : results) {
        t << "| " << benchMarkdown(r.graph.label);
        const auto bands = bandRmse(r.errors, bandColumnList.size());
        // Standard errors over seeds are kept for the perspective bands only (BenchSeeds.cpp
        // names them by index as 0-5, 5-20, 20+).
        const bool seedFigures = bandColumnList.size() == std::size(kBandFigures) &&
                                 bandColumnList[1].second == kBandFigures[1];
        for (size_t b = 0; b < bands.size(); ++b)
            t << " | " << benchNumber(bands[b], "%.5f")
              << (std::isnan(bands[b]) || !seedFigures
                      ? ""
                      : standardErrorSuffix(r.errors, kBandFigures[b], "%.5f"));
        t << " |\n";
    }
}

void passTable(std::ostream& t, const std::vector<BenchResult>& results) {
    t << "\n## GPU ms per pass (median over measured frames)\n\n"
      << "| Graph | Pass | Type | Median ms | Executions | Status (last frame) |\n"
      << "|---|---|---|---:|---:|---|\n";
    for (const auto& r : results)
        for (const auto& p : r.passes)
            t << "| " << benchMarkdown(r.graph.label) << " | " << benchMarkdown(p.name) << " | "
              << benchMarkdown(p.type) << " | " << benchNumber(p.gpuMs.median, "%.3f") << " | "
              << p.executions << " | " << p.status << " |\n";
}

// bench.md: the summary, the error tables, the per-band and per-pass breakdowns.
std::string markdownReport(const json& header, const std::vector<BenchResult>& results,
                           const BandColumns& bandColumnList) {
    std::ostringstream t;
    summaryParagraph(t, header, results);
    summaryTable(t, results);
    errorSections(t, header, results);
    bandTable(t, results, bandColumnList);
    seedTables(t, results);
    passTable(t, results);
    t << "\n![run time against error](bench.svg)\n";
    return t.str();
}

// bench.json: the header with every graph's results.
std::string benchJson(const json& header, const std::vector<BenchResult>& results) {
    json all = header;
    all["graphs"] = json::array();
    for (const auto& r : results) all["graphs"].push_back(resultJson(r));
    all["finished"] = true;
    return all.dump(2) + "\n";
}

}  // namespace

void writeBenchTables(const OutputFolder& folder, const json& header,
                      const std::vector<BenchResult>& results) {
    const BandColumns bandColumnList = bandColumns(results);
    folder.writeText("bench.csv", csvTable(header, results, bandColumnList));
    folder.writeText("bench.md", markdownReport(header, results, bandColumnList));
    // Written last: its presence and "finished" say that the folder is complete (as report.json).
    folder.writeText("bench.json", benchJson(header, results));
}

}  // namespace fovea::eval
