// `fovea gain` end to end (docs/gain-model.md): the JSON's `saving` is the library's
// (core/sampling/GainModel.h) for the presets and for explicit options, the text names every
// layout, and bad values exit 2 naming the option. CPU only (no device is created).
#include "core/sampling/GainModel.h"
#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;
namespace gs = fovea::sampling;

namespace {

// `fovea gain ARGS --json`, parsed; fails the test (returns null) when it did not exit 0.
json gainJson(std::vector<std::string> args) {
    args.insert(args.begin(), "gain");
    args.push_back("--json");
    const Result r = cli(args);
    EXPECT_EQ(r.code, 0) << r.describe();
    json j = json::parse(r.out, nullptr, false);
    EXPECT_FALSE(j.is_discarded()) << r.describe();
    return j.is_discarded() ? json() : j;
}

void expectGainSaving(const json& j, double expected, const std::string& what) {
    ASSERT_TRUE(j.contains("saving") && j["saving"].is_number()) << what << "\n" << j.dump(2);
    const double saving = j["saving"].get<double>();
    EXPECT_GE(saving, 0.0) << what;
    EXPECT_LE(saving, 1.0) << what;
    EXPECT_NEAR(saving, expected, 1e-12) << what;
    EXPECT_NEAR(j.at("relative_samples").get<double>(), 1.0 - expected, 1e-12) << what;
}

}  // namespace

TEST(CliGain, PresetsPrintTheLibrarysSaving) {
    for (const auto& preset : gs::displayPresets()) {
        const json j = gainJson({"--preset", preset.name});
        const gs::GainResult g = gs::foveationGain(preset.display);
        expectGainSaving(j, g.saving, preset.name);
        EXPECT_EQ(j.at("preset"), preset.name);
        EXPECT_EQ(j.at("p1_reported_saving").get<double>(), preset.reportedSaving);
        EXPECT_NEAR(j.at("required_integral").get<double>(), g.required, 1e-9 * g.required);
        EXPECT_NEAR(j.at("full_integral").get<double>(), g.full, 1e-9 * g.full);
        EXPECT_EQ(j.at("model").at("measure"), "flat");
        EXPECT_EQ(j.at("model").at("density"), "linear");
        // P1 §4's whole percents: 94 % and 70 %.
        EXPECT_NEAR(j.at("saving").get<double>(), preset.reportedSaving, 0.005) << preset.name;
        // The three layouts, each with its parameters.
        const json& layouts = j.at("layouts");
        EXPECT_GT(layouts.at("peres").at("r0_px").get<double>(), 0.0);
        EXPECT_EQ(layouts.at("peres").at("outer_probability").get<double>(), 0.5);
        EXPECT_EQ(layouts.at("visual_polar").at("reduction").get<double>(), 0.61);
        EXPECT_EQ(layouts.at("fv").at("budget").get<double>(), 100000.0);
        for (const char* key : {"table1", "tossed"}) {
            const double f = layouts.at("peres").at(key).at("fraction_of_base").get<double>();
            EXPECT_GT(f, 0.0) << key;
            EXPECT_LT(f, 1.0) << key;
        }
    }
    // The Vive: 1080 x 1200 per eye (P1 §4's 2160 x 1200), the layouts on that image.
    const json vive = gainJson({"--preset", "vive"});
    EXPECT_EQ(vive.at("display").at("resolution"), json::array({1080, 1200}));
    EXPECT_EQ(vive.at("layouts").at("eye_image").at("width"), 1080);
}

// Explicit options: cpd from the resolution (Nyquist, the smaller axis), an off-centre gaze and
// the non-default measure and density reach the library unchanged.
TEST(CliGain, ExplicitOptionsMatchTheLibrary) {
    gs::DisplayModel d;
    d.hfovDeg = 100;
    d.vfovDeg = 80;
    d.shape = gs::FovShape::Rectangle;
    d.width = 1920;
    d.height = 1080;
    d.cpd = std::min(1920.0 / 100.0 / 2.0, 1080.0 / 80.0 / 2.0);  // 6.75
    d.gazeDeg = {20, -10};
    const json j = gainJson({"--fov-deg", "100,80", "--shape", "rectangle", "--resolution",
                             "1920x1080", "--gaze-deg", "20,-10"});
    expectGainSaving(j, gs::foveationGain(d).saving, "rectangle");
    EXPECT_EQ(j.at("display").at("cpd").get<double>(), 6.75);
    EXPECT_EQ(j.at("display").at("gaze_deg"), json::array({20.0, -10.0}));

    gs::GainOptions options;
    options.measure = gs::AreaMeasure::Solid;
    options.density = gs::DetailDensity::Squared;
    const json solid =
        gainJson({"--fov-deg", "100,80", "--shape", "rectangle", "--resolution", "1920,1080",
                  "--gaze-deg", "20,-10", "--measure", "solid", "--density", "squared"});
    expectGainSaving(solid, gs::foveationGain(d, options).saving, "solid squared");

    // --cpd wins over the resolution's Nyquist cpd; the resolution stays the layouts' image.
    d.cpd = 12.5;
    const json cpd = gainJson({"--fov-deg", "100,80", "--shape", "rectangle", "--resolution",
                               "1920x1080", "--gaze-deg", "20,-10", "--cpd", "12.5"});
    expectGainSaving(cpd, gs::foveationGain(d).saving, "--cpd");
    EXPECT_EQ(cpd.at("layouts").at("eye_image").at("height"), 1080);
}

TEST(CliGain, TextNamesTheModelAndEveryLayout) {
    const Result r = cli({"gain", "--preset", "perfect-hmd"});
    ASSERT_EQ(r.code, 0) << r.describe();
    for (const char* fragment : {"93.81 %", "P1 §4 reports 94 %", "Peres", "Table 1 reading",
                                 "§3.2 reading", "Visual-Polar", "FV", "19200 x 16200"})
        EXPECT_TRUE(contains(r.out, fragment)) << fragment << "\n" << r.describe();
}

TEST(CliGain, BadValuesExit2NamingTheOption) {
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--preset", "quest2"}, "--preset"},
        {{"--fov-deg", "0", "--cpd", "10"}, "--fov-deg"},
        {{"--fov-deg", "-90", "--cpd", "10"}, "--fov-deg"},
        {{"--fov-deg", "400,100", "--cpd", "10"}, "--fov-deg"},
        {{"--fov-deg", "100,abc", "--cpd", "10"}, "--fov-deg"},
        {{"--fov-deg", "100,80", "--shape", "circle", "--cpd", "10"}, "--fov-deg"},
        {{"--fov-deg", "100", "--cpd", "0"}, "--cpd"},
        {{"--fov-deg", "100", "--cpd", "-3"}, "--cpd"},
        {{"--fov-deg", "100", "--cpd", "nan"}, "--cpd"},
        {{"--fov-deg", "100", "--cpd", "1e999"}, "--cpd"},
        {{"--fov-deg", "100"}, "--cpd"},
        {{"--cpd", "10"}, "--fov-deg"},
        {{"--fov-deg", "100", "--shape", "hexagon", "--cpd", "10"}, "--shape"},
        {{"--fov-deg", "100", "--resolution", "1920"}, "--resolution"},
        {{"--fov-deg", "100", "--resolution", "0,100"}, "--resolution"},
        {{"--fov-deg", "100", "--resolution", "10.5,100"}, "--resolution"},
        {{"--fov-deg", "100", "--cpd", "10", "--gaze-deg", "60,0"}, "--gaze-deg"},
        {{"--fov-deg", "100", "--cpd", "10", "--gaze-deg", "1"}, "--gaze-deg"},
        {{"--fov-deg", "360", "--shape", "rectangle", "--cpd", "10", "--measure", "solid"},
         "--measure"},
        {{"--fov-deg", "100", "--cpd", "10", "--density", "cubic"}, "--density"},
        {{"--fov-deg", "100", "--cpd", "10", "--peres-r0", "300", "--peres-r1", "200"},
         "--peres-r1"},
        {{"--fov-deg", "100", "--cpd", "10", "--peres-p", "2"}, "--peres-p"},
        {{"--fov-deg", "100", "--cpd", "10", "--vp-reduction", "0.95"}, "--vp-reduction"},
        {{"--fov-deg", "100", "--cpd", "10", "--vp-fovea-fraction", "0"}, "--vp-fovea-fraction"},
        {{"--fov-deg", "100", "--cpd", "10", "--fv-budget", "-1"}, "--fv-budget"},
        {{"--fov-deg", "", "--cpd", "10"}, "--fov-deg"},
    };
    for (const auto& [args, option] : cases) {
        std::vector<std::string> all = {"gain"};
        all.insert(all.end(), args.begin(), args.end());
        expectInputError(cli(all), {option});
    }
}
