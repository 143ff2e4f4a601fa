// Golden-image harness: runs a graph in-process (fovea::graph::RenderGraph on the test GPU
// context) for N frames at a small size and compares every marked output of the last frame with
// a stored reference, tests/goldens/<name>/<output>.exr, described by a JSON sidecar
// tests/goldens/<name>/<output>.json:
//
//   { "graph": "graphs/tests/utility_demo.json", "output": "acc.mean", "format": "rgba32f",
//     "size": [32, 32], "frames": 3, "seed": 1, "device": "llvmpipe (...)",
//     "driver": "llvmpipe Mesa ...", "tolerance": { "rmse": 1e-05, "max_abs": 0.0001 },
//     "created": "2025-01-01T12:00:00Z" }
//
// The sidecar's tolerance is the one compared against (edit it to loosen one golden); its graph,
// size, frames and seed must match the test, or the golden is stale. With the environment
// variable FOVEA_UPDATE_GOLDENS=1 the harness (re)writes the goldens instead of comparing.
// On a mismatch it writes the actual image and |actual - golden| into
// <cwd>/golden-failures/<name>/ and prints their paths with rmse and max_abs. docs/testing.md
// explains the workflow.
//
//   TEST_F(GoldenTest, Demo) {
//       fovea::test::GoldenSpec spec;
//       spec.name = "demo";
//       spec.graph = "graphs/tests/utility_demo.json";
//       EXPECT_TRUE(fovea::test::goldenMatches(ctx(), spec));
//   }
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/image/ImageCompare.h"
#include "core/image/ImageIO.h"

namespace fovea::gpu {
class Context;
}

namespace fovea::test {

// The repository root (parent of FOVEA_TEST_DIR).
std::filesystem::path repositoryRoot();
// tests/goldens in the source tree.
std::filesystem::path defaultGoldenRoot();
// <current working directory>/golden-failures (the build tree when run through ctest).
std::filesystem::path defaultFailureRoot();

struct GoldenTolerance {
    double rmse = 0;    // root mean squared error over the RGB channels of all pixels
    double maxAbs = 0;  // largest absolute difference of any RGB channel
    bool operator==(const GoldenTolerance&) const = default;
};

// Tolerance given to a new golden when the spec has none: one 8-bit code step for unorm formats,
// tight absolute bounds for float formats (see docs/testing.md for the reasoning).
GoldenTolerance defaultTolerance(const std::string& formatName);

enum class GoldenMode {
    FromEnvironment,  // Update if FOVEA_UPDATE_GOLDENS=1, else Compare
    Compare,
    Update,
};
// Compare or Update, as FOVEA_UPDATE_GOLDENS says.
GoldenMode modeFromEnvironment();

struct GoldenSpec {
    std::string name;             // goldens go to <goldenRoot>/<name>/
    std::filesystem::path graph;  // relative paths are relative to the repository root
    uint32_t width = 32, height = 32;
    uint32_t frames = 3;
    std::optional<uint64_t> seed;  // unset: the graph's default seed, else 0 (as `fovea run`)
    // A scene ("builtin:cornell" or a glTF path relative to the repository root) seen through
    // its first camera (else the default framing camera), optionally as a side-by-side stereo
    // pair. Empty: no scene. Both are part of the golden's identity when a scene is set.
    std::string scene;
    bool stereo = false;
    // A camera path file relative to the repository root (its camera, gaze and camera model per
    // frame) instead of the scene's camera; part of the identity when set.
    std::string cameraPath;
    // Parameter overrides { "pass": { "param": value } } applied to the graph file (like
    // `fovea run --set`), e.g. foveation radii scaled to the small test size. Part of the
    // golden's identity when set.
    nlohmann::json params = nlohmann::json::object();
    // Tolerance for newly created goldens (an existing sidecar's tolerance is kept on update);
    // unset: defaultTolerance() of the output's format.
    std::optional<GoldenTolerance> tolerance;
    std::filesystem::path goldenRoot = defaultGoldenRoot();
    std::filesystem::path failureRoot = defaultFailureRoot();
    GoldenMode mode = GoldenMode::FromEnvironment;
};

enum class GoldenStatus {
    Match,      // within tolerance
    Mismatch,   // over tolerance (actual + difference written)
    Missing,    // no golden image or sidecar
    Stale,      // sidecar made for another graph/size/frames/seed, or no longer an output
    Invalid,    // unreadable golden/sidecar, or a non-finite value in a new golden
    Written,    // update mode: golden (re)written
    Unchanged,  // update mode: golden already bit-identical, left untouched
};
const char* goldenStatusName(GoldenStatus s);

struct GoldenOutputResult {
    std::string output;  // "acc.mean"; for an orphaned golden, its file stem
    GoldenStatus status = GoldenStatus::Match;
    image::CompareResult compare;  // Match / Mismatch only
    GoldenTolerance tolerance;
    std::filesystem::path golden;      // <goldenRoot>/<name>/<output>.exr
    std::filesystem::path actual;      // written on Mismatch/Missing/Stale, else empty
    std::filesystem::path difference;  // written on Mismatch, else empty
    std::string message;               // one line (or a few) saying what happened
};

struct GoldenReport {
    GoldenMode mode = GoldenMode::Compare;  // the mode actually used
    std::vector<GoldenOutputResult> outputs;
    bool ok() const;              // every output Match / Written / Unchanged
    std::string summary() const;  // every output's message, one block
};

// The last-frame content of every alive marked output, in graph order, and the device used.
struct RenderedOutput {
    std::string output;  // "pass.field"
    std::string format;  // "rgba32f", "rgba8", ...
    image::ImageRGBA image;
};
std::vector<RenderedOutput> renderGraphOutputs(gpu::Context& ctx, const GoldenSpec& spec,
                                               uint64_t& seedUsed);

// Renders and compares (or updates). Input errors (bad graph) propagate as exceptions.
GoldenReport runGolden(gpu::Context& ctx, const GoldenSpec& spec);

// runGolden for tests: success, or failure carrying the summary; in update mode prints what
// it wrote.
::testing::AssertionResult goldenMatches(gpu::Context& ctx, const GoldenSpec& spec);

}  // namespace fovea::test
