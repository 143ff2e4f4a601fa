// Parsing of `fovea bench` files (docs/bench.md). Every error names the file and the JSON
// pointer of the offending value; paths are relative to the bench file's folder.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/scene/Camera.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"
#include "core/util/InstallPaths.h"
#include "core/util/JsonUtil.h"
#include "core/util/UserFile.h"
#include "eval/bench/Bench.h"

namespace fovea::eval {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

class Reader {
public:
    explicit Reader(std::string file) : mFile(std::move(file)) {}
    [[noreturn]] void fail(const std::string& pointer, const std::string& message) const {
        throw InputError(mFile, pointer, message);
    }
    void keys(const json& j, const std::string& pointer,
              const std::vector<std::string>& allowed) const {
        if (!j.is_object()) fail(pointer.empty() ? "/" : pointer, "expected an object");
        for (const auto& [key, value] : j.items())
            if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
                fail(pointer + "/" + key, "unknown field '" + key + "'" + didYouMean(key, allowed));
    }
    const json& need(const json& j, const std::string& pointer, const std::string& key) const {
        if (!j.contains(key)) fail(pointer.empty() ? "/" : pointer, "missing field '" + key + "'");
        return j[key];
    }
    std::string string(const json& j, const std::string& pointer) const {
        if (!j.is_string() || j.get<std::string>().empty())
            fail(pointer, "expected a non-empty string");
        return j.get<std::string>();
    }
    uint32_t count(const json& j, const std::string& pointer, uint32_t min, uint32_t max) const {
        if (!j.is_number_integer() || j.get<int64_t>() < min || j.get<int64_t>() > max)
            fail(pointer, "expected an integer in [" + std::to_string(min) + ", " +
                              std::to_string(max) + "]");
        return uint32_t(j.get<int64_t>());
    }
    // A finite number in [min, max].
    double number(const json& j, const std::string& pointer, double min, double max) const {
        if (!j.is_number() || !std::isfinite(j.get<double>()) || j.get<double>() < min ||
            j.get<double>() > max) {
            char range[64];
            std::snprintf(range, sizeof range, "[%g, %g]", min, max);
            fail(pointer, std::string("expected a finite number in ") + range);
        }
        return j.get<double>();
    }
    std::vector<std::string> strings(const json& j, const std::string& pointer) const {
        if (!j.is_array()) fail(pointer, "expected an array of strings");
        std::vector<std::string> out;
        for (size_t i = 0; i < j.size(); ++i)
            out.push_back(string(j[i], pointer + "/" + std::to_string(i)));
        return out;
    }
    // A path relative to the bench file's folder.
    fs::path resolve(const json& j, const std::string& pointer) const {
        std::string text = string(j, pointer);
        fs::path p =
            fs::path(text).is_absolute() ? fs::path(text) : fs::path(mFile).parent_path() / text;
        if (const std::string problem = pathProblem(p.string()); !problem.empty())
            fail(pointer, problem);
        return p;
    }
    // The same, and it must exist.
    std::string path(const json& j, const std::string& pointer, const char* what) const {
        fs::path p = resolve(j, pointer);
        if (!fs::exists(p)) fail(pointer, what + std::string(" '") + p.string() + "' not found");
        return p.lexically_normal().string();
    }

private:
    std::string mFile;
};

BenchReference parseReference(const Reader& r, const json& j) {
    BenchReference ref;
    if (j.is_string() && j.get<std::string>() == "render") {
        ref.render = true;
    } else if (j.is_string()) {
        // Checked when the run starts (after --out): a reference is often rendered into out/
        // first (scripts/benchmarks.sh), so a bench file may name one that does not exist yet.
        ref.file = r.resolve(j, "/reference").lexically_normal().string();
    } else if (j.is_object()) {
        r.keys(j, "/reference", {"render"});
        const json& render = r.need(j, "/reference", "render");
        r.keys(render, "/reference/render", {"spp", "graph", "set", "output"});
        ref.render = true;
        if (render.contains("spp"))
            ref.spp = r.count(render["spp"], "/reference/render/spp", 1, 1u << 24);
        if (render.contains("graph"))
            ref.graph = r.path(render["graph"], "/reference/render/graph", "graph file");
        if (render.contains("output"))
            ref.output = r.string(render["output"], "/reference/render/output");
        if (render.contains("set")) ref.sets = r.strings(render["set"], "/reference/render/set");
    } else {
        r.fail("/reference", "expected an EXR path, \"render\" or {\"render\": {\"spp\": N, ...}}");
    }
    if (ref.render && ref.graph.empty()) ref.graph = shippedGraph("reference.json");
    return ref;
}

// `env`: "sky.exr" or {"file": "sky.exr", "intensity": 1, "rotation": 0} (--env and its options;
// the file relative to the bench file). The ranges are those of the command-line options.
void parseEnvironment(const Reader& r, const json& j, BenchSpec& spec) {
    if (j.is_string()) {
        spec.env = r.path(j, "/env", "environment map");
        return;
    }
    if (!j.is_object())
        r.fail("/env",
               "expected the environment map's file name or {\"file\": ..., "
               "\"intensity\": ..., \"rotation\": ...}");
    r.keys(j, "/env", {"file", "intensity", "rotation"});
    spec.env = r.path(r.need(j, "/env", "file"), "/env/file", "environment map");
    if (j.contains("intensity"))
        spec.envIntensity = float(r.number(j["intensity"], "/env/intensity", 0.0, 1e9));
    if (j.contains("rotation"))
        spec.envRotation = float(r.number(j["rotation"], "/env/rotation", -36000.0, 36000.0));
}

// `seeds`: the alternative to `seed`, every graph runs once per seed (BenchSeeds.cpp).
std::vector<uint64_t> parseSeeds(const Reader& r, const json& j) {
    if (j.contains("seed"))
        r.fail("/seeds", "give either /seed (one run seed) or /seeds (several), not both");
    const json& s = j["seeds"];
    if (!s.is_array() || s.empty()) r.fail("/seeds", "expected a non-empty array of integers");
    std::vector<uint64_t> seeds;
    for (size_t i = 0; i < s.size(); ++i) {
        const std::string pointer = "/seeds/" + std::to_string(i);
        const uint64_t seed = r.count(s[i], pointer, 0, 0xffffffffu);
        if (std::find(seeds.begin(), seeds.end(), seed) != seeds.end())
            r.fail(pointer, "seed " + std::to_string(seed) + " is given twice");
        seeds.push_back(seed);
    }
    return seeds;
}

// `flip`: false (no ꟻLIP), true (the defaults) or {"mode": "auto"|"ldr"|"hdr", "ppd": number |
// "camera"} (ReferenceErrors.h FlipChoice).
FlipChoice parseFlip(const Reader& r, const json& f) {
    FlipChoice choice;
    if (f.is_boolean()) {
        choice.enabled = f.get<bool>();
        return choice;
    }
    if (!f.is_object()) r.fail("/flip", "expected true, false or {\"mode\", \"ppd\"}");
    r.keys(f, "/flip", {"mode", "ppd"});
    if (f.contains("mode")) {
        choice.mode = r.string(f["mode"], "/flip/mode");
        if (choice.mode != "auto" && choice.mode != "ldr" && choice.mode != "hdr")
            r.fail("/flip/mode", "expected \"auto\", \"ldr\" or \"hdr\"");
    }
    if (f.contains("ppd")) {
        const json& p = f["ppd"];
        const std::string text =
            p.is_string() ? p.get<std::string>() : (p.is_number() ? p.dump() : std::string());
        if (!parseFlipPpd(text, choice))
            r.fail("/flip/ppd", "expected \"camera\" or a finite number > 0");
    }
    return choice;
}

void checkTopLevelFields(const Reader& r, const json& j) {
    r.keys(
        j, "",
        {"version",      "name",      "description", "scene",        "camera", "size", "stereo",
         "camera_model", "sun",       "env",         "frames",       "warmup", "seed", "seeds",
         "output",       "reference", "noise_floor", "also_against", "layers", "flip", "graphs"});
}

// `scene`: a file relative to the bench file, or a built-in scene ("builtin:...") that is not
// a file at all; `camera`: a camera path file.
void parseSceneAndCamera(const Reader& r, const json& j, BenchSpec& spec) {
    const std::string scene = r.string(r.need(j, "", "scene"), "/scene");
    spec.scene = scene.rfind("builtin:", 0) == 0 ? scene : r.path(j["scene"], "/scene", "scene");
    if (j.contains("camera")) spec.camera = r.path(j["camera"], "/camera", "camera path");
}

// `size`, `stereo` and `camera_model`; the 2:1 check of an equirect image needs both the size
// and the model, so it comes after them.
void parseImage(const Reader& r, const json& j, BenchSpec& spec) {
    const json& size = r.need(j, "", "size");
    if (!size.is_array() || size.size() != 2) r.fail("/size", "expected [width, height]");
    spec.width = r.count(size[0], "/size/0", 1, 16384);
    spec.height = r.count(size[1], "/size/1", 1, 16384);
    if (j.contains("stereo")) {
        if (!j["stereo"].is_boolean()) r.fail("/stereo", "expected true or false");
        spec.stereo = j["stereo"].get<bool>();
    }
    if (j.contains("camera_model")) {
        spec.cameraModel = r.string(j["camera_model"], "/camera_model");
        if (!scene::parseCameraModel(spec.cameraModel))
            r.fail("/camera_model", "expected \"perspective\" or \"equirect\"");
    }
    if (spec.cameraModel == "equirect" && spec.width != 2 * spec.height)
        r.fail("/size", "an equirect camera needs a 2:1 image (width twice the height)");
}

// `sun` and `env`, the lights added for every graph and the reference.
void parseLighting(const Reader& r, const json& j, BenchSpec& spec) {
    if (j.contains("sun")) {
        if (!j["sun"].is_boolean()) r.fail("/sun", "expected true or false");
        spec.sun = j["sun"].get<bool>();
    }
    if (j.contains("env")) parseEnvironment(r, j["env"], spec);
}

// `frames`, `warmup` (at least one frame must be left to measure) and `seed` or `seeds`.
void parseFramesAndSeeds(const Reader& r, const json& j, BenchSpec& spec) {
    spec.frames = r.count(r.need(j, "", "frames"), "/frames", 1, 1u << 20);
    if (j.contains("warmup")) spec.warmup = r.count(j["warmup"], "/warmup", 0, 1u << 20);
    if (spec.warmup >= spec.frames)
        r.fail("/warmup", "warm-up (" + std::to_string(spec.warmup) +
                              ") leaves no measured frame of " + std::to_string(spec.frames));
    if (j.contains("seed")) spec.seeds = {r.count(j["seed"], "/seed", 0, 0xffffffffu)};
    if (j.contains("seeds")) spec.seeds = parseSeeds(r, j);
}

// `noise_floor`: "render" (needs a rendered reference) or a second reference file.
void parseNoiseFloor(const Reader& r, const json& n, BenchSpec& spec) {
    if (n.is_string() && n.get<std::string>() == "render") {
        if (!spec.reference.render)
            r.fail("/noise_floor",
                   "\"render\" needs a rendered /reference; name a second reference file "
                   "(another seed) instead");
        spec.noiseFloorRender = true;
    } else if (n.is_string()) {
        spec.noiseFloor = r.resolve(n, "/noise_floor").lexically_normal().string();
    } else {
        r.fail("/noise_floor",
               "expected \"render\" or the path of a second reference with another seed");
    }
}

// `also_against`: more references, each with a unique label other than "reference".
std::vector<BenchAgainst> parseAlsoAgainst(const Reader& r, const json& a) {
    if (!a.is_array()) r.fail("/also_against", "expected an array of {\"label\", \"reference\"}");
    std::vector<BenchAgainst> against;
    for (size_t i = 0; i < a.size(); ++i) {
        BenchAgainst g;
        g.pointer = "/also_against/" + std::to_string(i);
        r.keys(a[i], g.pointer, {"label", "reference", "noise_floor"});
        g.label = r.string(r.need(a[i], g.pointer, "label"), g.pointer + "/label");
        if (g.label == "reference")
            r.fail(g.pointer + "/label", "'reference' names the bench's own reference");
        for (const auto& other : against)
            if (other.label == g.label)
                r.fail(g.pointer + "/label", "label '" + g.label + "' is used twice");
        // Checked when the run starts, like /reference (it may be rendered first).
        g.file = r.resolve(r.need(a[i], g.pointer, "reference"), g.pointer + "/reference")
                     .lexically_normal()
                     .string();
        if (a[i].contains("noise_floor"))
            g.noiseFloor = r.resolve(a[i]["noise_floor"], g.pointer + "/noise_floor")
                               .lexically_normal()
                               .string();
        against.push_back(std::move(g));
    }
    return against;
}

// `layers`: the radii of the per-layer errors, {"r0", "r1", "unit": "pixels"|"degrees"}.
eval::LayerRadii parseLayers(const Reader& r, const json& l) {
    r.keys(l, "/layers", {"r0", "r1", "unit"});
    auto radius = [&](const char* key) {
        const json& v = r.need(l, "/layers", key);
        const std::string pointer = std::string("/layers/") + key;
        if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < 0)
            r.fail(pointer, "expected a finite number >= 0");
        return v.get<double>();
    };
    eval::LayerRadii radii;
    radii.r0 = radius("r0");
    radii.r1 = radius("r1");
    if (radii.r1 < radii.r0) r.fail("/layers/r1", "r1 is smaller than r0");
    if (l.contains("unit")) {
        const std::string unit = r.string(l["unit"], "/layers/unit");
        if (unit != "pixels" && unit != "degrees")
            r.fail("/layers/unit", "expected \"pixels\" or \"degrees\"");
        radii.degrees = unit == "degrees";
    }
    return radii;
}

// `graphs`: the graphs to run, each with a unique label (default: the file's stem).
std::vector<BenchGraph> parseGraphs(const Reader& r, const json& graphs) {
    if (!graphs.is_array() || graphs.empty()) r.fail("/graphs", "expected a non-empty array");
    std::vector<BenchGraph> out;
    for (size_t i = 0; i < graphs.size(); ++i) {
        BenchGraph g;
        g.pointer = "/graphs/" + std::to_string(i);
        r.keys(graphs[i], g.pointer, {"file", "label", "set", "output"});
        g.file = r.path(r.need(graphs[i], g.pointer, "file"), g.pointer + "/file", "graph file");
        g.label = graphs[i].contains("label") ? r.string(graphs[i]["label"], g.pointer + "/label")
                                              : fs::path(g.file).stem().string();
        if (graphs[i].contains("set")) g.sets = r.strings(graphs[i]["set"], g.pointer + "/set");
        if (graphs[i].contains("output"))
            g.output = r.string(graphs[i]["output"], g.pointer + "/output");
        for (const auto& other : out)
            if (other.label == g.label)
                r.fail(g.pointer + "/label", "label '" + g.label + "' is used twice");
        out.push_back(std::move(g));
    }
    return out;
}

}  // namespace

// The stages run in a fixed order: the first error reported for a bad file must not change.
BenchSpec parseBenchFile(const fs::path& file) {
    const std::string name = file.string();
    // parseJsonText: line and column of a syntax error, the nesting and NUL-byte limits.
    json j = parseJsonText(readUserTextFile(file, kMaxJsonFileBytes, "bench file"), name);
    Reader r(name);
    checkTopLevelFields(r, j);
    BenchSpec spec;
    spec.file = name;
    if (r.count(r.need(j, "", "version"), "/version", 1, 1) != 1) r.fail("/version", "expected 1");
    spec.name = j.contains("name") ? r.string(j["name"], "/name") : file.stem().string();
    parseSceneAndCamera(r, j, spec);
    parseImage(r, j, spec);
    parseLighting(r, j, spec);
    parseFramesAndSeeds(r, j, spec);
    if (j.contains("output")) spec.output = r.string(j["output"], "/output");
    spec.reference = parseReference(r, r.need(j, "", "reference"));
    if (j.contains("noise_floor")) parseNoiseFloor(r, j["noise_floor"], spec);
    if (j.contains("also_against")) spec.against = parseAlsoAgainst(r, j["also_against"]);
    if (j.contains("flip")) spec.flip = parseFlip(r, j["flip"]);
    if (j.contains("layers")) spec.layers = parseLayers(r, j["layers"]);
    spec.graphs = parseGraphs(r, r.need(j, "", "graphs"));
    return spec;
}

}  // namespace fovea::eval
