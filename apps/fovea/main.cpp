// fovea: run, validate and list render graphs. Exit codes: 0 ok, 1 runtime failure,
// 2 bad input or usage. Every error is caught here: no crash, no uncaught exception.
#include <iostream>

#include "apps/fovea/Commands.h"
#include "core/graph/PassRegistry.h"
#include "core/util/Error.h"

int main(int argc, char** argv) {
    using namespace fovea::app;
    CLI::App app{"fovea " FOVEA_VERSION " — render graphs for foveated path tracing and denoising"};
    app.require_subcommand(1);
    app.set_version_flag("--version", FOVEA_VERSION);
    RunOptions run;
    ValidateOptions validate;
    PassesOptions passes;
    addRunCommand(app, run);
    addValidateCommand(app, validate);
    addPassesCommand(app, passes);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        app.exit(e);
        return kExitInput;
    }
    try {
        fovea::registerBuiltinPasses();
        if (app.got_subcommand("run")) return runCommand(run);
        if (app.got_subcommand("validate")) return validateCommand(validate);
        if (app.got_subcommand("passes")) return passesCommand(passes);
    } catch (const fovea::InputError& e) {
        std::cerr << "error: " << e.what() << "\n";
        return kExitInput;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return kExitRuntime;
    }
    return kExitInput;
}
