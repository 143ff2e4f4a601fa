// `fovea gain`: P1's theoretical foveation gain of a display (seed 003 P1 §4,
// core/sampling/GainModel.h) and, for the same display, the samples fovea's three foveated
// layouts trace: Peres' three layers (seed 000), Koskela's Visual-Polar grid (seed 003 P5) and
// P4's fixed-budget FV. CPU only. Every bad value is an input error (exit 2) naming its option.
#include <array>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <tuple>

#include "apps/fovea/CliChecks.h"
#include "apps/fovea/Commands.h"
#include "core/sampling/GainModel.h"
#include "core/sampling/VisualPolar.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"

namespace fovea::app {

namespace {

using sampling::DisplayModel;

// The largest resolution per eye axis and FV budget accepted (far beyond any HMD).
constexpr double kMaxPixels = 1000000.0;
constexpr double kMaxBudget = 1e12;

double parseNumber(const std::string& text, const std::string& option) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v))
        throw InputError(option + ": expected a finite number, got '" + text + "'");
    return v;
}

// "A,B" (also "AxB" where `allowX`), or "A" when `allowSingle` (then B = A).
std::array<double, 2> parsePair(const std::string& text, const std::string& option,
                                bool allowSingle, bool allowX) {
    const size_t cut = text.find_first_of(allowX ? ",x" : ",");
    if (cut == std::string::npos) {
        if (!allowSingle)
            throw InputError(option + ": expected two numbers 'A,B', got '" + text + "'");
        const double v = parseNumber(text, option);
        return {v, v};
    }
    return {parseNumber(text.substr(0, cut), option), parseNumber(text.substr(cut + 1), option)};
}

double checked(double v, double lo, double hi, bool openLo, const std::string& option) {
    if (v < lo || v > hi || (openLo && v == lo))
        throw InputError(option + ": expected a value in " + (openLo ? "(" : "[") +
                         shortNumber(lo) + ", " + shortNumber(hi) + "], got " + shortNumber(v));
    return v;
}

template <class T>
T choose(const std::string& text, const std::string& option,
         const std::vector<std::pair<std::string, T>>& choices) {
    std::vector<std::string> names;
    for (const auto& [name, value] : choices) {
        if (text == name) return value;
        names.push_back(name);
    }
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InputError(option + ": unknown value '" + text + "'" + didYouMean(text, names) +
                     " (one of: " + list + ")");
}

struct GainInputs {
    DisplayModel display;
    const sampling::DisplayPreset* preset = nullptr;
    bool asPublished = false;  // a preset with P1's own display and reading: its number applies
    std::string cpdSource, resolutionSource, radiiSource;
    sampling::GainOptions model;
    double r0 = 0, r1 = 0, p = 0.5, vpReduction = 0.61, vpFoveaFraction = 0.24, fvBudget = 0;
};

// --preset, --shape, --fov-deg, --resolution, --cpd and --gaze-deg: the display, with where
// each value came from.
void parseDisplay(const GainOptions& o, GainInputs& in) {
    if (!o.preset.empty()) {
        std::vector<std::pair<std::string, const sampling::DisplayPreset*>> presets;
        for (const auto& p : sampling::displayPresets()) presets.push_back({p.name, &p});
        in.preset = choose(o.preset, "--preset", presets);
        in.display = in.preset->display;
    }
    DisplayModel& d = in.display;
    if (!o.shape.empty())
        d.shape = choose<sampling::FovShape>(o.shape, "--shape",
                                             {{"oval", sampling::FovShape::Oval},
                                              {"rectangle", sampling::FovShape::Rectangle},
                                              {"circle", sampling::FovShape::Circle}});
    if (!o.fov.empty()) {
        const auto fov = parsePair(o.fov, "--fov-deg", true, false);
        d.hfovDeg = checked(fov[0], 0.0, sampling::kMaxFovDegrees, true, "--fov-deg");
        d.vfovDeg = checked(fov[1], 0.0, sampling::kMaxFovDegrees, true, "--fov-deg");
    } else if (!in.preset) {
        throw InputError("--fov-deg: required without --preset (presets: perfect-hmd, vive)");
    }
    if (d.shape == sampling::FovShape::Circle && d.hfovDeg != d.vfovDeg)
        throw InputError("--fov-deg: a circle needs one diameter, got " + shortNumber(d.hfovDeg) +
                         "," + shortNumber(d.vfovDeg));
    const std::string presetName = in.preset ? std::string("preset ") + in.preset->name : "";
    if (!o.resolution.empty()) {
        const auto res = parsePair(o.resolution, "--resolution", false, true);
        for (double v : res)
            if (v != std::floor(v))
                throw InputError("--resolution: expected whole pixels, got '" + o.resolution + "'");
        d.width = uint32_t(checked(res[0], 1.0, kMaxPixels, false, "--resolution"));
        d.height = uint32_t(checked(res[1], 1.0, kMaxPixels, false, "--resolution"));
        in.resolutionSource = "--resolution";
    } else if (d.width > 0) {
        in.resolutionSource = presetName;
    }
    if (!o.cpd.empty()) {
        d.cpd = checked(parseNumber(o.cpd, "--cpd"), 0.0, sampling::kMaxDisplayCpd, true, "--cpd");
        in.cpdSource = "--cpd";
    } else if (!o.resolution.empty()) {
        // Nyquist per axis; the smaller: the detail the display shows in every direction.
        d.cpd = std::min(sampling::nyquistCpd(d.width, d.hfovDeg),
                         sampling::nyquistCpd(d.height, d.vfovDeg));
        in.cpdSource = "--resolution (Nyquist, the smaller axis)";
    } else if (in.preset) {
        in.cpdSource = presetName;
    } else {
        throw InputError("--cpd: give --cpd or --resolution (or --preset)");
    }
    if (in.resolutionSource.empty()) {
        in.resolutionSource = "2 pixels per cycle at the display's cpd over the FOV";
        const auto eye = sampling::eyeImageOf(d);  // derives width/height from cpd
        d.width = eye.width;
        d.height = eye.height;
    }
    if (!o.gaze.empty()) {
        const auto g = parsePair(o.gaze, "--gaze-deg", false, false);
        d.gazeDeg = {g[0], g[1]};
    }
}

// --measure and --density, then the model's own checks of the display.
void parseModel(const GainOptions& o, GainInputs& in) {
    const DisplayModel& d = in.display;
    in.model.measure = choose<sampling::AreaMeasure>(
        o.measure, "--measure",
        {{"flat", sampling::AreaMeasure::Flat}, {"solid", sampling::AreaMeasure::Solid}});
    in.model.density =
        choose<sampling::DetailDensity>(o.density, "--density",
                                        {{"linear", sampling::DetailDensity::Linear},
                                         {"squared", sampling::DetailDensity::Squared}});
    // The model's own checks (gaze inside the FOV, solid angle within 180 degrees, a cpd from
    // --resolution in range), prefixed with the option that set the value.
    try {
        sampling::checkDisplay(d, in.model.measure);
    } catch (const InputError& e) {
        const std::string what = e.what();
        auto startsWith = [&](const char* prefix) { return what.rfind(prefix, 0) == 0; };
        std::string option = "--fov-deg";
        if (startsWith("gaze")) option = "--gaze-deg";
        if (startsWith("solid")) option = "--measure";
        if (startsWith("cycles")) option = o.cpd.empty() ? "--resolution" : "--cpd";
        throw InputError(option + ": " + what);
    }
}

// The pipelines' parameters the gains are computed for: Peres r0/r1/p, Visual-Polar reduction
// and fovea fraction, the foveated-preview budget.
void parsePipelineParameters(const GainOptions& o, GainInputs& in) {
    const DisplayModel& d = in.display;
    // Seed 000 Table 1's radii (144 / 288 px at 1080 rows) scaled by the eye height, as the
    // pipelines do (docs/pipelines.md), unless given.
    const double scale = d.height / sampling::kPeresTable1Rows;
    in.r0 = o.peresR0.empty() ? sampling::kPeresTable1R0 * scale
                              : checked(parseNumber(o.peresR0, "--peres-r0"), 0.0, kMaxPixels,
                                        false, "--peres-r0");
    in.r1 = o.peresR1.empty() ? std::max(sampling::kPeresTable1R1 * scale, in.r0)
                              : checked(parseNumber(o.peresR1, "--peres-r1"), 0.0, kMaxPixels,
                                        false, "--peres-r1");
    if (in.r1 < in.r0)
        throw InputError("--peres-r1: " + shortNumber(in.r1) +
                         " is smaller than r0 = " + shortNumber(in.r0));
    in.radiiSource = o.peresR0.empty() && o.peresR1.empty()
                         ? "Table 1's 144 / 288 px at 1080 rows, scaled by the eye height"
                         : "--peres-r0 / --peres-r1";
    in.p = checked(parseNumber(o.peresP, "--peres-p"), 0.0, 1.0, false, "--peres-p");
    // VisualPolarWarp's parameter ranges.
    in.vpReduction =
        checked(parseNumber(o.vpReduction, "--vp-reduction"), 0.5, 0.88, false, "--vp-reduction");
    in.vpFoveaFraction =
        checked(parseNumber(o.vpFoveaFraction, "--vp-fovea-fraction"),
                sampling::kVisualPolarMinFoveaFraction, 0.5, false, "--vp-fovea-fraction");
    in.fvBudget =
        checked(parseNumber(o.fvBudget, "--fv-budget"), 0.0, kMaxBudget, false, "--fv-budget");
}

GainInputs parseInputs(const GainOptions& o) {
    GainInputs in;
    parseDisplay(o, in);
    parseModel(o, in);
    parsePipelineParameters(o, in);
    in.asPublished = in.preset && o.fov.empty() && o.shape.empty() && o.cpd.empty() &&
                     o.resolution.empty() && o.gaze.empty() &&
                     in.model.measure == sampling::AreaMeasure::Flat &&
                     in.model.density == sampling::DetailDensity::Linear;
    return in;
}

// printf to stdout (the format checked by the compiler).
__attribute__((format(printf, 1, 2))) void say(const char* format, ...) {
    char text[1024];
    va_list args;
    va_start(args, format);
    std::vsnprintf(text, sizeof text, format, args);
    va_end(args);
    std::cout << text;
}

std::string percent(double fraction) {
    char text[32];
    std::snprintf(text, sizeof text, "%.2f %%", 100.0 * fraction);
    return text;
}

std::string count(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.0f", v);
    return text;
}

}  // namespace

void addGainCommand(CLI::App& app, GainOptions& o) {
    auto* cmd = app.add_subcommand(
        "gain",
        "P1's theoretical foveation gain of a display (seed 003 P1 §4) and the samples fovea's "
        "foveated layouts trace on it");
    auto text = [&](const char* name, std::string& value, const char* help) {
        cmd->add_option(name, value, help)->check(nonEmptyValue());
    };
    text("--preset", o.preset, "perfect-hmd or vive (P1 §4); other options override its values");
    text("--fov-deg", o.fov, "field of view H,V in degrees (one value: both), each in (0, 360]");
    text("--shape", o.shape, "FOV shape: oval (default), rectangle or circle (H = V)");
    text("--cpd", o.cpd, "cycles per degree the display shows, in (0, 1000]");
    text("--resolution", o.resolution,
         "pixels per eye W,H; without --cpd, cpd = pixels / FOV / 2 (the smaller axis)");
    text("--gaze-deg", o.gaze, "gaze X,Y in degrees from the FOV centre (default 0,0: P1's bound)");
    text("--measure", o.measure,
         "FOV area: flat (polar degrees, P1's reading, default) or solid (solid angle)");
    text("--density", o.density,
         "samples proportional to cpd: linear (P1's reading, default) or squared (cpd^2)");
    text("--peres-r0", o.peresR0, "Peres fovea radius in pixels (default: Table 1's, scaled)");
    text("--peres-r1", o.peresR1, "Peres middle-ring outer radius in pixels (>= r0)");
    text("--peres-p", o.peresP, "Peres outer probability p for §3.2's toss (default 0.5)");
    text("--vp-reduction", o.vpReduction, "VisualPolarWarp reduction, 0.5-0.88 (default 0.61)");
    text("--vp-fovea-fraction", o.vpFoveaFraction,
         "VisualPolarWarp foveaFraction, 0.1-0.5 (default 0.24)");
    text("--fv-budget", o.fvBudget,
         "P4 FV samples per frame (default 100000: P4 §4, ~100,000 per 14 ms frame)");
    cmd->add_flag("--json", o.json, "print one JSON object (the saving under `saving`)");
}

namespace {

// Everything `fovea gain` prints, computed once for the JSON and the text form.
struct GainReport {
    const GainInputs& in;
    sampling::GainResult g;
    sampling::EyeImage eye;
    sampling::PeresCounts peres;
    sampling::VisualPolarCounts vp;
    sampling::FvCounts fv;
    double pixels = 0;  // of the eye image
};

constexpr const char* kAreaUnit = "deg^2";

void printGainJson(const GainReport& r) {
    const GainInputs& in = r.in;
    const DisplayModel& d = in.display;
    const auto& [g, eye, peres, vp, fv, pixels] =
        std::tie(r.g, r.eye, r.peres, r.vp, r.fv, r.pixels);
    const char* areaUnit = kAreaUnit;
    using nlohmann::json;
    json j;
    j["preset"] = in.preset ? json(in.preset->name) : json(nullptr);
    if (in.asPublished) j["p1_reported_saving"] = in.preset->reportedSaving;
    j["display"] = {
        {"fov_deg", {d.hfovDeg, d.vfovDeg}},
        {"shape", sampling::toString(d.shape)},
        {"cpd", d.cpd},
        {"cpd_source", in.cpdSource},
        {"resolution", {d.width, d.height}},
        {"resolution_source", in.resolutionSource},
        {"nyquist_cpd",
         {sampling::nyquistCpd(d.width, d.hfovDeg), sampling::nyquistCpd(d.height, d.vfovDeg)}},
        {"gaze_deg", {d.gazeDeg.x, d.gazeDeg.y}}};
    j["model"] = {{"acuity", "P1 Eq. 2, capped at the display's cpd"},
                  {"measure", sampling::toString(in.model.measure)},
                  {"density", sampling::toString(in.model.density)},
                  {"angular_steps", in.model.angularSteps}};
    j["saving"] = g.saving;
    j["relative_samples"] = g.relativeSamples;
    j["required_integral"] = g.required;
    j["full_integral"] = g.full;
    j["fov_area"] = g.area;
    j["area_unit"] = areaUnit;
    j["cutoff_deg"] = g.cutoffDeg;
    j["max_eccentricity_deg"] = g.maxEccentricityDeg;
    j["error_estimate"] = g.errorEstimate;
    json layers = json::array();
    for (int l = 0; l < 3; ++l)
        layers.push_back({{"spp", sampling::kPeresSpp[l]},
                          {"area_px", peres.area[l]},
                          {"sampled_px", peres.sampled[l]}});
    j["layouts"] = {{"eye_image",
                     {{"width", eye.width},
                      {"height", eye.height},
                      {"gaze_px", {eye.gazePx.x, eye.gazePx.y}},
                      {"pixels", pixels}}},
                    {"peres",
                     {{"r0_px", peres.r0},
                      {"r1_px", peres.r1},
                      {"radii_source", in.radiiSource},
                      {"outer_probability", peres.outerProbability},
                      {"layers", layers},
                      {"base_samples", peres.baseSamples},
                      {"table1",
                       {{"samples", peres.table1Samples},
                        {"fraction_of_base", peres.table1Samples / peres.baseSamples}}},
                      {"tossed",
                       {{"samples", peres.tossedSamples},
                        {"fraction_of_base", peres.tossedSamples / peres.baseSamples}}}}},
                    {"visual_polar",
                     {{"reduction", vp.reduction},
                      {"fovea_fraction", vp.foveaFraction},
                      {"grid", {vp.gridWidth, vp.gridHeight}},
                      {"valid_texels", vp.validTexels},
                      {"traced_texels", vp.tracedTexels},
                      {"fraction_of_pixels", double(vp.tracedTexels) / pixels}}},
                    {"fv",
                     {{"budget", fv.budget},
                      {"inside_fov_fraction", fv.insideFraction},
                      {"samples_in_fov", fv.samplesInFov},
                      {"fraction_of_frame", fv.frameFraction},
                      {"samples_per_pixel_at_gaze", fv.gazeSpp}}}};
    std::cout << j.dump(2) << "\n";
}

void printGainText(const GainReport& r) {
    const GainInputs& in = r.in;
    const DisplayModel& d = in.display;
    const auto& [g, eye, peres, vp, fv, pixels] =
        std::tie(r.g, r.eye, r.peres, r.vp, r.fv, r.pixels);
    const char* areaUnit = kAreaUnit;
    if (in.preset) say("display   %s: %s\n", in.preset->name, in.preset->source);
    say("          %s FOV %g x %g deg, %g c/deg (%s), gaze (%g, %g) deg from the FOV centre\n",
        sampling::toString(d.shape), d.hfovDeg, d.vfovDeg, d.cpd, in.cpdSource.c_str(), d.gazeDeg.x,
        d.gazeDeg.y);
    say("model     P1 Eq. 2 acuity M(e) capped at %g c/deg; area: %s; samples ~ %s\n", d.cpd,
        in.model.measure == sampling::AreaMeasure::Flat ? "flat polar degrees (P1's reading)"
                                                        : "solid angle",
        in.model.density == sampling::DetailDensity::Linear ? "cpd (P1's reading)" : "cpd^2");
    say("saving    %s of the samples can be omitted", percent(g.saving).c_str());
    if (in.asPublished) say(" (P1 §4 reports %.0f %%)", 100.0 * in.preset->reportedSaving);
    say("; quadrature error estimate %.1e\n", g.errorEstimate);
    say("          required: integral of min(M(e), cpd) over the FOV = %.6g c/deg x %s\n",
        g.required, areaUnit);
    say("          full:     cpd x FOV area = %.6g (area %.6g %s); traced share %s\n", g.full,
        g.area, areaUnit, percent(g.relativeSamples).c_str());
    say("          the display out-resolves the eye beyond %.3g deg; farthest FOV point %.4g "
        "deg\n\n",
        g.cutoffDeg, g.maxEccentricityDeg);
    say("What fovea's foveated layouts trace on one %u x %u eye image (%s; Nyquist %.3g x %.3g "
        "c/deg),\nall of its rectangle (also outside an oval or circular FOV), gaze at pixel "
        "(%.1f, %.1f):\n",
        eye.width, eye.height, in.resolutionSource.c_str(),
        sampling::nyquistCpd(eye.width, d.hfovDeg), sampling::nyquistCpd(eye.height, d.vfovDeg),
        eye.gazePx.x, eye.gazePx.y);
    say("  Peres 3 layers (seed 000 §3.2, FoveationMask): r0 = %.1f px, r1 = %.1f px (%s), "
        "spp 4/3/2\n",
        peres.r0, peres.r1, in.radiiSource.c_str());
    say("    Table 1 reading, every pixel of each layer: %s samples = %s of Base (4 spp at "
        "every pixel), saving %s\n",
        count(peres.table1Samples).c_str(),
        percent(peres.table1Samples / peres.baseSamples).c_str(),
        percent(1.0 - peres.table1Samples / peres.baseSamples).c_str());
    say("    §3.2 reading, toss 1 -> p = %g in the middle, p outside: %s samples = %s of Base, "
        "saving %s\n",
        peres.outerProbability, count(peres.tossedSamples).c_str(),
        percent(peres.tossedSamples / peres.baseSamples).c_str(),
        percent(1.0 - peres.tossedSamples / peres.baseSamples).c_str());
    say("  Visual-Polar (seed 003 P5, VisualPolarWarp): reduction %g, foveaFraction %g, stereo "
        "grid %u x %u per eye\n",
        vp.reduction, vp.foveaFraction, vp.gridWidth, vp.gridHeight);
    say("    %llu texels traced (centre on screen; %llu valid) = %s of the eye's pixels at 1 "
        "spp, saving %s\n",
        (unsigned long long)vp.tracedTexels, (unsigned long long)vp.validTexels,
        percent(double(vp.tracedTexels) / pixels).c_str(),
        percent(1.0 - double(vp.tracedTexels) / pixels).c_str());
    say("  FV (seed 003 P4): a fixed budget of %s samples per frame (--fv-budget), m(e) "
        "density to 80 deg\n",
        count(fv.budget).c_str());
    say("    %s land in the FOV: %s samples = %s of one 1-spp eye image; %.3g samples per "
        "pixel per frame at the gaze\n",
        percent(fv.insideFraction).c_str(), count(fv.samplesInFov).c_str(),
        percent(fv.frameFraction).c_str(), fv.gazeSpp);
}

}  // namespace

int gainCommand(const GainOptions& o) {
    const GainInputs in = parseInputs(o);
    const DisplayModel& d = in.display;
    GainReport r{in, sampling::foveationGain(d, in.model), sampling::eyeImageOf(d), {}, {}, {}, 0};
    r.peres = sampling::peresCounts(r.eye, in.r0, in.r1, in.p);
    r.vp = sampling::visualPolarCounts(r.eye, in.vpReduction, in.vpFoveaFraction);
    r.fv = sampling::fvCounts(d, in.fvBudget);
    r.pixels = double(r.eye.width) * r.eye.height;
    if (o.json)
        printGainJson(r);
    else
        printGainText(r);
    return kExitOk;
}

}  // namespace fovea::app
