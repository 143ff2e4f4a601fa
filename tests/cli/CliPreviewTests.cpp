// The equirect camera model and the 360° preview graphs from the command line (issue 27): the
// three graphs run on any scene, their count output adds up to the budget, the 2:1 size rule,
// stereo and bad camera_model values are exit 2 naming the option or JSON pointer, and
// `run --reference` splits the error into P4's foveal bands for an equirect camera.
#include <map>

#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

const fs::path kPreviewGraphs[] = {kRepo / "graphs" / "preview_od.json",
                                   kRepo / "graphs" / "preview_vp.json",
                                   kRepo / "graphs" / "preview_fv.json"};

// Sum of the first channel of an EXR (the count image is r32f, written as grey).
double previewChannelSum(const fs::path& exr) {
    const auto img = ::fovea::image::readImage(exr);
    double sum = 0;
    for (size_t i = 0; i < img.pixels.size(); i += 4) sum += img.pixels[i];
    return sum;
}

}  // namespace

TEST(CliPreview, EveryMethodSpendsTheSameBudgetOnAnyScene) {
    TempDir dir;
    for (const auto& graph : kPreviewGraphs) {
        const fs::path out = dir / graph.stem().string();
        // Another scene than the graph's: the graph's camera path is dropped, the scene's own
        // camera is used, the model stays equirect (defaults.camera_model).
        const Result r =
            cli({"run", graph.string(), "--scene", "builtin:plane", "--size", "64x32", "--frames",
                 "3", "--set", "samples.budget=500", "--set", "preview.width=32", "--set",
                 "preview.height=24", "--out", out.string()});
        ASSERT_EQ(r.code, 0) << r.describe();
        EXPECT_EQ(previewChannelSum(out / "acc.count.frame0002.exr"), 1500.0) << graph;
        const auto view = ::fovea::image::readImage(out / "preview.view.frame0002.exr");
        EXPECT_EQ(view.width, 32u);
        EXPECT_EQ(view.height, 24u);
        const json report = readReport(out);
        EXPECT_EQ(report.at("scene").at("camera_model"), "equirect") << graph;
    }
}

TEST(CliPreview, EquirectNeedsATwoToOneMonoImage) {
    TempDir dir;
    expectInputError(cli({"run", kPathTraceGraph.string(), "--camera-model", "equirect", "--size",
                          "64x64", "--out", (dir / "a").string()}),
                     {"--size", "twice the height", "64x64"});
    expectInputError(cli({"run", kPathTraceGraph.string(), "--camera-model", "equirect", "--size",
                          "64x32", "--stereo", "--out", (dir / "b").string()}),
                     {"--stereo", "one eye"});
    expectInputError(cli({"run", kPathTraceGraph.string(), "--camera-model", "fisheye"}),
                     {"--camera-model", "fisheye"});
    // The graph's default size is 2:1, --size 64x48 is not: validate says so too.
    expectInputError(cli({"validate", kPreviewGraphs[2].string(), "--size", "64x48"}),
                     {"--size", "64x48"});
    // A preview graph forced onto a pinhole: PreviewSamples refuses, naming the parameter.
    expectInputError(cli({"validate", kPreviewGraphs[0].string(), "--camera-model", "perspective",
                          "--size", "64x32"}),
                     {"/passes/0/params/method", "--camera-model equirect"});
}

TEST(CliPreview, CameraModelFieldsAreCheckedWhereTheyAreWritten) {
    TempDir dir;
    const fs::path path = dir / "path.json";
    writeText(path, R"({ "version": 1, "camera_model": "cube", "keyframes": [ { "frame": 0,
                         "position": [0, 1, 3], "target": [0, 1, 0] } ] })");
    expectInputError(cli({"run", kPathTraceGraph.string(), "--camera", path.string(), "--size",
                          "64x32", "--out", (dir / "a").string()}),
                     {"path.json", "/camera_model", "equirect"});
    const fs::path graph = dir / "graph.json";
    writeText(graph, R"({ "version": 1, "defaults": { "camera_model": "360" }, "passes": [
                          { "name": "src", "type": "ImageSource" } ], "outputs": ["src.color"] })");
    expectInputError(cli({"validate", graph.string()}),
                     {"graph.json", "/defaults/camera_model", "perspective"});
    // A camera path may choose the model: 2:1 then applies.
    writeText(path, R"({ "version": 1, "camera_model": "equirect", "keyframes": [ { "frame": 0,
                         "position": [278, 250, 250], "target": [278, 250, 559] } ] })");
    expectInputError(cli({"run", kPathTraceGraph.string(), "--camera", path.string(), "--size",
                          "64x64", "--out", (dir / "b").string()}),
                     {"--size", "twice the height"});
    const Result ok = cli({"run", kPathTraceGraph.string(), "--camera", path.string(), "--size",
                           "64x32", "--out", (dir / "c").string()});
    EXPECT_EQ(ok.code, 0) << ok.describe();
}

// run --reference with an equirect camera reports P4's bands (0-5, 5-10, 10-20, 20-80, 80+
// degrees around the gaze on the sphere); FV's foveal band gets more samples than OD's and so
// less error after the same frames.
TEST(CliPreview, ReferenceErrorsUseSphericalBandsAndFavourTheFovea) {
    TempDir dir;
    const Result ref = cli({"reference", "--scene", "builtin:cornell", "--camera",
                            (kRepo / "graphs" / "cameras" / "cornell_360.json").string(), "--size",
                            "64x32", "--spp", "64", "--out", (dir / "ref").string(), "--quiet"});
    ASSERT_EQ(ref.code, 0) << ref.describe();
    fs::path refExr;  // the reference's last frame, acc.mean.frameNNNN.exr
    for (const auto& e : fs::directory_iterator(dir / "ref"))
        if (e.path().extension() == ".exr" && contains(e.path().filename().string(), "acc.mean"))
            refExr = e.path();
    ASSERT_FALSE(refExr.empty());
    std::map<std::string, double> fovea;
    for (int k : {0, 2}) {
        const fs::path out = dir / kPreviewGraphs[k].stem().string();
        const Result r = cli({"run", kPreviewGraphs[k].string(), "--size", "64x32", "--frames", "4",
                              "--set", "samples.budget=400", "--reference", refExr.string(),
                              "--reference-output", "acc.mean", "--out", out.string()});
        ASSERT_EQ(r.code, 0) << r.describe();
        const json bands = readReport(out).at("reference").at("mean").at("bands");
        ASSERT_EQ(bands.size(), 5u) << bands.dump();
        EXPECT_EQ(bands[1].at("from"), 5.0);
        EXPECT_EQ(bands[2].at("from"), 10.0);
        EXPECT_EQ(bands[4].at("from"), 80.0);
        EXPECT_GT(bands[0].at("pixels").get<int>(), 0);
        fovea[kPreviewGraphs[k].stem().string()] = bands[0].at("rmse").get<double>();
    }
    EXPECT_LT(fovea["preview_fv"], 0.5 * fovea["preview_od"]);
}

TEST(CliPreview, BenchChecksTheEquirectSize) {
    TempDir dir;
    const fs::path bench = dir / "bench.json";
    writeText(bench, R"({ "version": 1, "scene": "builtin:cornell", "camera_model": "equirect",
        "size": [64, 64], "frames": 2, "reference": { "render": { "graph": ")" +
                         (kRepo / "graphs" / "reference.json").generic_string() +
                         R"(", "output": "acc.mean", "spp": 4 } }, "graphs": [ { "file": ")" +
                         kPreviewGraphs[2].generic_string() + R"(" } ] })");
    expectInputError(cli({"bench", bench.string(), "--out", (dir / "out").string()}),
                     {"bench.json", "/size", "2:1"});
    // The shipped preview bench is 2:1; forcing equirect onto a square bench file is refused too.
    expectInputError(cli({"bench", (kRepo / "graphs" / "benches" / "demo_spp.json").string(),
                          "--camera-model", "equirect", "--out", (dir / "out2").string()}),
                     {"--camera-model", "2:1", "128x128"});
}

// The pinhole-only foveation passes refuse an equirect camera with the parameter's pointer
// instead of computing discs and polar grids on a 360° image.
TEST(CliPreview, PinholeFoveationPassesRefuseAnEquirectCamera) {
    for (const char* graph : {"peres_nh3ld.json", "koskela_vp_bmfr.json"}) {
        const Result r = cli({"validate", (kRepo / "graphs" / graph).string(), "--camera-model",
                              "equirect", "--mono", "--size", "64x32"});
        expectInputError(r, {graph, "/params/", "perspective camera"});
    }
}
