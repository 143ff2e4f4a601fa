// Bench files (`fovea bench FILE`): the reader with its checks of every field, path and seed.
// Paths in a bench file are relative to its folder, so the input is written where the project's
// own bench files live, graphs/benches/, in a copy of graphs/ made of links to the real files: the
// seeds' "../koskela_bmfr.json" and "../cameras/..." then exist, and the reader gets past them.
#include "eval/bench/Bench.h"
#include "tests/fuzz/FuzzInput.h"

namespace {

void linkProjectGraphs() {
    namespace fs = std::filesystem;
    const fs::path graphs = fovea::fuzz::inputFolder() / "graphs";
    fs::create_directories(graphs / "benches");
    for (const auto& entry : fs::directory_iterator(fs::path(FOVEA_SOURCE_DIR) / "graphs"))
        if (entry.path().filename() != "benches" && !fs::exists(graphs / entry.path().filename()))
            fs::create_symlink(entry.path(), graphs / entry.path().filename());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace fovea;
    static const bool linked = (linkProjectGraphs(), true);
    (void)linked;
    fuzz::expectOnlyInputErrors("bench_file", [&] {
        (void)eval::parseBenchFile(fuzz::writeInput(data, size, "graphs/benches/bench.json"));
    });
    return 0;
}
