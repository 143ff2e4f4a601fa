// The command line (`fovea ARGS...`): one argument per line of the input. CLI11's parse with every
// subcommand, flag and validator main() has (apps/fovea/Cli.h), the unknown-subcommand message,
// then the checks a command makes before it touches the device or writes a file: the graph file
// with its --set overrides (loadGraph) and the render and window sizes, and all of `gain` (CPU
// only, its output discarded). Nothing is rendered or written.
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "apps/fovea/Cli.h"
#include "passes/RegisterPasses.h"
#include "tests/fuzz/FuzzInput.h"

namespace {

std::vector<std::string> splitLines(const uint8_t* data, size_t size) {
    std::vector<std::string> args{"fovea"};
    std::string current;
    for (size_t i = 0; i < size && args.size() < 64; ++i) {
        if (data[i] == '\n') {
            args.push_back(current);
            current.clear();
        } else {
            current.push_back(char(data[i]));
        }
    }
    if (!current.empty()) args.push_back(current);
    return args;
}

void checkGraphOptions(const fovea::app::GraphOptions& graph) {
    const fovea::graph::GraphDesc desc = fovea::app::loadGraph(graph);
    (void)fovea::app::renderSize(graph, desc);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace fovea;
    registerBuiltinPasses();
    const std::vector<std::string> args = splitLines(data, size);
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    CLI::App app{"fovea"};
    app::CliOptions o;
    app::addCommands(app, o);
    try {
        app.parse(int(argv.size()), argv.data());
    } catch (const CLI::Error&) {
        (void)app::unknownSubcommand(app, int(argv.size()), argv.data());
        return 0;
    }
    fuzz::expectOnlyInputErrors("cli", [&] {
        if (app.got_subcommand("run")) checkGraphOptions(o.run.graph);
        if (app.got_subcommand("reference")) checkGraphOptions(o.reference.run.graph);
        if (app.got_subcommand("validate")) checkGraphOptions(o.validate.graph);
        // gain needs no device: the whole command runs, its printout discarded.
        if (app.got_subcommand("gain")) {
            std::ostringstream sink;
            std::streambuf* saved = std::cout.rdbuf(sink.rdbuf());
            try {
                (void)app::gainCommand(o.gain);
            } catch (...) {
                std::cout.rdbuf(saved);
                throw;
            }
            std::cout.rdbuf(saved);
        }
        if (app.got_subcommand("inspect")) {
            checkGraphOptions(o.inspect.graph);
            (void)app::parseSize(o.inspect.window, "--window");
        }
    });
    return 0;
}
