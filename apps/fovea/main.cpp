// fovea: run, validate and list render graphs. Exit codes: 0 ok, 1 runtime failure,
// 2 bad input or usage. Every error is caught here: no crash, no uncaught exception.
#include <algorithm>
#include <iostream>

#include "apps/fovea/Commands.h"
#include "core/graph/PassRegistry.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"
#include "core/util/JsonUtil.h"
#include "passes/RegisterPasses.h"

namespace {

// CLI11 answers an unknown first word with "A subcommand is required" only. Returns the message
// naming it (with a suggestion and the list), or "" when the first word is a subcommand or absent.
std::string unknownSubcommand(CLI::App& app, int argc, char** argv) {
    std::string word;
    for (int i = 1; i < argc && word.empty(); ++i)
        if (argv[i][0] != '-') word = argv[i];
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        names.push_back(sub->get_name());
    if (word.empty() || std::find(names.begin(), names.end(), word) != names.end()) return "";
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    return "unknown subcommand '" + word + "'" + fovea::didYouMean(word, names) +
           " (subcommands: " + list + ")";
}

}  // namespace

int main(int argc, char** argv) {
    using namespace fovea::app;
    CLI::App app{"fovea " FOVEA_VERSION " — render graphs for foveated path tracing and denoising"};
    app.require_subcommand(1);
    app.set_version_flag("--version", FOVEA_VERSION);
    RunOptions run;
    ValidateOptions validate;
    PassesOptions passes;
    ReferenceOptions reference;
    CompareOptions compare;
    BenchOptions bench;
    InspectOptions inspect;
    addRunCommand(app, run);
    addReferenceCommand(app, reference);
    addValidateCommand(app, validate);
    addPassesCommand(app, passes);
    addCompareCommand(app, compare);
    addBenchCommand(app, bench);
    addInspectCommand(app, inspect);
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
        fovea::registerBuiltinPasses();
        if (app.got_subcommand("run")) return runCommand(run);
        if (app.got_subcommand("reference")) return referenceCommand(reference);
        if (app.got_subcommand("validate")) return validateCommand(validate);
        if (app.got_subcommand("passes")) return passesCommand(passes);
        if (app.got_subcommand("compare")) return compareCommand(compare);
        if (app.got_subcommand("bench")) return benchCommand(bench);
        if (app.got_subcommand("inspect")) return inspectCommand(inspect);
    } catch (const fovea::InputError& e) {
        // Quoted user text (a pass type, a key) is cut at 200 characters: one readable line.
        std::cerr << "error: " << fovea::shortenQuotedSpans(e.what()) << "\n";
        return kExitInput;
    } catch (const std::exception& e) {
        std::cerr << "error: " << fovea::shortenQuotedSpans(e.what()) << "\n";
        return kExitRuntime;
    }
    return kExitInput;
}
