// `fovea bench` over several seeds (bench key `seeds`, docs/bench.md "Several seeds"): the errors
// of every graph as means over the seeds with their standard error, and the paired difference of
// every graph against the first one. Why: on builtin:forest 512² the 0-5 deg band of one seed is
// dominated by a few 1-spp fireflies that BMFR's history keeps for frames, so one seed can say
// "graph B is worse" while the mean over six seeds says the opposite (docs/bench.md). Pairing
// (same seed, same samples for both graphs) removes the noise the two graphs share.
#include <algorithm>
#include <cmath>
#include <set>

#include "eval/bench/Bench.h"

namespace fovea::eval {

using nlohmann::json;

namespace {

double meanOf(const std::vector<double>& v) {
    double sum = 0;
    for (double x : v) sum += x;
    return v.empty() ? std::nan("") : sum / double(v.size());
}

// Sample standard deviation over the seeds / sqrt(seeds): the standard error of their mean. One
// value has no spread to measure: 0 (a bench with several seeds has at least two).
double standardErrorOf(const std::vector<double>& v) {
    if (v.size() < 2) return 0.0;
    const double m = meanOf(v);
    double squares = 0;
    for (double x : v) squares += (x - m) * (x - m);
    return std::sqrt(squares / double(v.size() - 1)) / std::sqrt(double(v.size()));
}

// Keys that describe a figure (which band, which unit) rather than measure an error: the same in
// every seed, kept as they are in the standard-error object.
bool describesFigure(const std::string& key) {
    static const std::set<std::string> kKeys = {"from",  "to",   "pixels",         "unit",
                                                "layer", "peak", "rel_mse_epsilon"};
    return kKeys.count(key) > 0;
}

// The numbers of `values` (JSON null = +inf, an infinite PSNR); false when one is neither.
bool numbersOf(const std::vector<const json*>& values, std::vector<double>& out) {
    out.clear();
    for (const json* v : values) {
        if (v->is_null()) {
            out.push_back(INFINITY);
        } else if (v->is_number()) {
            out.push_back(v->get<double>());
        } else {
            return false;
        }
    }
    return true;
}

// Applies `reduce` to every number of the seeds' objects, key by key (arrays index by index);
// describing keys, strings and booleans are kept as the first seed has them.
template <class Reduce>
json combine(const std::vector<const json*>& values, const std::string& key, Reduce reduce) {
    const json& first = *values.front();
    // Strings and booleans are no figures (and an object equal in every seed still has a spread
    // of 0, so it is reduced like the others).
    if (describesFigure(key) || first.is_string() || first.is_boolean()) return first;
    if (first.is_object()) {
        json out = json::object();
        for (const auto& [k, _] : first.items()) {
            std::vector<const json*> children;
            for (const json* v : values)
                if (v->is_object() && v->contains(k)) children.push_back(&(*v)[k]);
            if (children.size() == values.size()) out[k] = combine(children, k, reduce);
        }
        return out;
    }
    if (first.is_array()) {
        json out = json::array();
        for (size_t i = 0; i < first.size(); ++i) {
            std::vector<const json*> children;
            for (const json* v : values)
                if (v->is_array() && v->size() == first.size()) children.push_back(&(*v)[i]);
            if (children.size() == values.size()) out.push_back(combine(children, key, reduce));
        }
        return out;
    }
    std::vector<double> numbers;
    if (!numbersOf(values, numbers)) return first;
    const double r = reduce(numbers);
    return std::isfinite(r) ? json(r) : json(nullptr);  // JSON has no infinity (PSNR)
}

struct Figure {
    const char* name;
    const char* list;  // "bands" or "layers" of the errors' "mean"; null: a key of "mean" itself
    size_t index;
    double scale;  // layers: RMSE % = 100 RMSE (the bench compares with peak 1, ImageMetrics.h)
};
const Figure kFigures[] = {{"rmse", nullptr, 0, 1},
                           {"rmse_percent", nullptr, 0, 1},
                           {"rmse_0_5deg", "bands", 0, 1},
                           {"rmse_5_20deg", "bands", 1, 1},
                           {"rmse_20deg_plus", "bands", 2, 1},
                           {"rmse_percent_fovea", "layers", 0, 100},
                           {"rmse_percent_middle", "layers", 1, 100},
                           {"rmse_percent_outer", "layers", 2, 100},
                           {"flip_mean", nullptr, 0, 1}};

// A figure of an errors "mean" (or "standard_error") object; NaN when it has none.
double figureOf(const json& mean, const Figure& f) {
    const json* v = nullptr;
    if (!f.list) {
        if (mean.contains(f.name)) v = &mean[f.name];
    } else if (mean.contains(f.list) && mean[f.list].size() > f.index &&
               mean[f.list][f.index].contains("rmse")) {
        v = &mean[f.list][f.index]["rmse"];
    }
    return v && v->is_number() ? f.scale * v->get<double>() : std::nan("");
}

const Figure& figureNamed(const std::string& name) {
    for (const auto& f : kFigures)
        if (name == f.name) return f;
    return kFigures[0];  // the names come from seedFigureNames()
}

// "mean ± s.e." of a difference figure, bold and marked when |mean| > 2 s.e.
std::string differenceCell(const json& difference, const std::string& name, const char* format) {
    if (!difference.contains("figures") || !difference["figures"].contains(name)) return "—";
    const json& d = difference["figures"][name];
    const std::string text = benchNumber(d.at("mean").get<double>(), format) + " ± " +
                             benchNumber(d.at("standard_error").get<double>(), format);
    return d.at("significant").get<bool>() ? "**" + text + " (> 2 s.e.)**" : text;
}

}  // namespace

double benchFigure(const json& errors, const std::string& figure) {
    return errors.contains("mean") ? figureOf(errors["mean"], figureNamed(figure)) : std::nan("");
}

const std::vector<std::string>& seedFigureNames() {
    static const std::vector<std::string> kNames = [] {
        std::vector<std::string> names;
        for (const auto& f : kFigures) names.push_back(f.name);
        return names;
    }();
    return kNames;
}

json combineSeedErrors(const std::vector<uint64_t>& seeds, const std::vector<json>& perSeed) {
    std::vector<const json*> means;
    std::vector<double> temporal;
    json out = {{"seeds", json::array()}};
    for (size_t s = 0; s < perSeed.size(); ++s) {
        means.push_back(&perSeed[s].at("mean"));
        temporal.push_back(perSeed[s].at("temporal_error").get<double>());
        json one = perSeed[s];
        one["seed"] = seeds[s];
        out["seeds"].push_back(one);
        if (perSeed[s].contains("worst") &&
            (!out.contains("worst") || perSeed[s]["worst"].at("rmse").get<double>() >
                                           out["worst"].at("rmse").get<double>())) {
            out["worst"] = perSeed[s]["worst"];
            out["worst"]["seed"] = seeds[s];
        }
    }
    out["mean"] = combine(means, "", meanOf);
    out["standard_error"] = combine(means, "", standardErrorOf);
    out["temporal_error"] = meanOf(temporal);
    out["temporal_error_standard_error"] = standardErrorOf(temporal);
    return out;
}

eval::ImageMetrics meanOverSeeds(const std::vector<eval::ImageMetrics>& perSeed) {
    eval::ImageMetrics m = perSeed.front();
    auto mean = [&](double eval::ImageMetrics::*field) {
        std::vector<double> v;
        for (const auto& p : perSeed) v.push_back(p.*field);
        m.*field = meanOf(v);  // PSNR: +inf when any seed's is (identical images)
    };
    for (auto field :
         {&eval::ImageMetrics::mse, &eval::ImageMetrics::rmse, &eval::ImageMetrics::rmsePercent,
          &eval::ImageMetrics::relMse, &eval::ImageMetrics::psnr, &eval::ImageMetrics::ssim,
          &eval::ImageMetrics::meanAbsLuminanceDiff, &eval::ImageMetrics::flipMean})
        mean(field);
    return m;
}

json pairedDifference(const json& graph, const json& first, const std::string& firstLabel) {
    json figures = json::object();
    const json& a = graph.at("seeds");
    const json& b = first.at("seeds");
    for (const auto& f : kFigures) {
        std::vector<double> d;
        for (size_t s = 0; s < a.size() && s < b.size(); ++s) {
            // Paired: the same seed in both graphs (combineSeedErrors keeps the bench's order).
            if (a[s].at("seed") != b[s].at("seed")) break;
            d.push_back(figureOf(a[s].at("mean"), f) - figureOf(b[s].at("mean"), f));
        }
        if (d.size() != a.size() || d.size() != b.size() ||
            std::any_of(d.begin(), d.end(), [](double x) { return std::isnan(x); }))
            continue;  // a figure one of the graphs does not have (no bands, no layers)
        const double mean = meanOf(d), se = standardErrorOf(d);
        figures[f.name] = {{"seeds", d},
                           {"mean", mean},
                           {"standard_error", se},
                           {"significant", std::abs(mean) > 2 * se}};
    }
    return {{"against", firstLabel}, {"figures", figures}};
}

std::string seedCsvHeader() {
    std::string h = ",seeds";
    for (const auto& f : kFigures) h += std::string(",") + f.name + "_se";
    for (const auto& f : kFigures)
        h += std::string(",diff_") + f.name + ",diff_" + f.name + "_se,diff_" + f.name +
             "_significant";
    return h;
}

std::string seedCsvRow(const BenchResult& r) {
    std::string row = ",";
    for (const auto& s : r.errors.at("seeds"))
        row += (row.size() > 1 ? " " : "") + std::to_string(s.at("seed").get<uint64_t>());
    for (const auto& f : kFigures)
        row += "," + benchNumber(figureOf(r.errors.at("standard_error"), f), "%.6g");
    for (const auto& f : kFigures) {
        const json* d = r.difference.contains("figures") && r.difference["figures"].contains(f.name)
                            ? &r.difference["figures"][f.name]
                            : nullptr;
        if (!d) {
            row += ",nan,nan,";
            continue;
        }
        row += "," + benchNumber(d->at("mean").get<double>(), "%.6g") + "," +
               benchNumber(d->at("standard_error").get<double>(), "%.6g") + "," +
               (d->at("significant").get<bool>() ? "true" : "false");
    }
    return row;
}

std::string standardErrorSuffix(const json& errors, const std::string& figure, const char* format) {
    if (!errors.contains("standard_error")) return "";
    return " ± " + benchNumber(figureOf(errors["standard_error"], figureNamed(figure)), format);
}

void seedTables(std::ostream& t, const std::vector<BenchResult>& results) {
    const json& first = results.front().errors;
    if (!first.contains("seeds")) return;
    const bool layers = !std::isnan(figureOf(first.at("mean"), figureNamed("rmse_percent_fovea")));
    const std::vector<std::string> columns =
        layers ? std::vector<std::string>{"rmse",
                                          "rmse_0_5deg",
                                          "rmse_5_20deg",
                                          "rmse_20deg_plus",
                                          "rmse_percent_fovea",
                                          "rmse_percent_middle",
                                          "rmse_percent_outer"}
               : std::vector<std::string>{"rmse", "rmse_0_5deg", "rmse_5_20deg", "rmse_20deg_plus"};
    const std::string headings = std::string("RMSE | 0-5 deg | 5-20 deg | 20+ deg") +
                                 (layers ? " | RMSE % fovea | RMSE % middle | RMSE % outer" : "");
    const std::string align =
        layers ? "---:|---:|---:|---:|---:|---:|---:|" : "---:|---:|---:|---:|";
    auto format = [](const std::string& name) {
        return name.rfind("rmse_percent", 0) == 0 ? "%.4f" : "%.5f";
    };

    t << "\n## Each seed (its mean over the measured frames)\n\n| Graph | Seed | " << headings
      << " | Temporal error |\n|---|---:|" << align << "---:|\n";
    for (const auto& r : results)
        for (const auto& s : r.errors.at("seeds")) {
            t << "| " << benchMarkdown(r.graph.label) << " | " << s.at("seed").get<uint64_t>();
            for (const auto& c : columns)
                t << " | " << benchNumber(figureOf(s.at("mean"), figureNamed(c)), format(c));
            t << " | " << benchNumber(s.at("temporal_error").get<double>(), "%.5f") << " |\n";
        }

    if (results.size() < 2) return;
    const std::string& base = results.front().graph.label;
    t << "\n## Difference against " << benchMarkdown(base) << " (paired over seeds)\n\n"
      << "Per seed the graph's error minus " << base
      << "'s with the same seed, then the mean over the " << first.at("seeds").size()
      << " seeds ± its standard error (sample standard deviation / sqrt(seeds)). Negative: "
         "closer to the reference than "
      << base
      << ". **Bold (> 2 s.e.)**: the difference is larger than twice its standard error, more "
         "than the seed-to-seed spread explains; otherwise these seeds do not resolve it.\n\n"
      << "| Graph | " << headings << " |\n|---|" << align << "\n";
    for (size_t i = 1; i < results.size(); ++i) {
        t << "| " << benchMarkdown(results[i].graph.label);
        for (const auto& c : columns)
            t << " | " << differenceCell(results[i].difference, c, format(c));
        t << " |\n";
    }
}

}  // namespace fovea::eval
