// fovea: run, validate and list render graphs. Exit codes: 0 ok, 1 runtime failure,
// 2 bad input or usage. Every error is caught here: no crash, no uncaught exception.
#include <iostream>

#include "apps/fovea/Cli.h"
#include "core/util/Error.h"
#include "core/util/JsonUtil.h"

int main(int argc, char** argv) {
    using namespace fovea::app;
    CLI::App app{"fovea " FOVEA_VERSION " — render graphs for foveated path tracing and denoising"};
    CliOptions options;
    addCommands(app, options);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        if (std::string unknown = unknownSubcommand(app, argc, argv); !unknown.empty()) {
            std::cerr << "error: " << unknown << "\nRun with --help for more information.\n";
            return kExitInput;
        }
        app.exit(e);
        return kExitInput;
    }
    try {
        return runSubcommand(app, options);
    } catch (const fovea::InputError& e) {
        // Quoted user text (a pass type, a key) is cut at 200 characters: one readable line.
        std::cerr << "error: " << fovea::shortenQuotedSpans(e.what()) << "\n";
        return kExitInput;
    } catch (const std::exception& e) {
        std::cerr << "error: " << fovea::shortenQuotedSpans(e.what()) << "\n";
        return kExitRuntime;
    }
}
