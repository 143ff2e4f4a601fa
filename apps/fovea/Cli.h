// The command line of `fovea`: every subcommand's options in one struct, the CLI11 app that fills
// them, and the dispatch to the chosen subcommand. main() and the CLI fuzz target
// (tests/fuzz/FuzzCli.cpp) build the same parser from here.
#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "apps/fovea/Commands.h"

namespace fovea::app {

struct CliOptions {
    RunOptions run;
    ValidateOptions validate;
    PassesOptions passes;
    ReferenceOptions reference;
    MergeOptions merge;
    CompareOptions compare;
    BenchOptions bench;
    InspectOptions inspect;
    GainOptions gain;
    DevicesOptions devices;
    std::vector<std::string> plugins;  // --plugin of whichever subcommand ran
};

// Adds every subcommand to `app` (which must outlive nothing but `options`).
void addCommands(CLI::App& app, CliOptions& options);

// CLI11 answers an unknown first word with "A subcommand is required" only. Returns the message
// naming it (with a suggestion and the list), or "" when the first word is a subcommand or absent.
std::string unknownSubcommand(CLI::App& app, int argc, const char* const* argv);

// Registers the built-in pass types and the plugins of --plugin and FOVEA_PLUGIN_PATH, then runs
// the subcommand `app` parsed. Exceptions propagate (main maps them to exit codes).
int runSubcommand(const CLI::App& app, const CliOptions& options);

}  // namespace fovea::app
