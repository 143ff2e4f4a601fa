#include "apps/fovea/Cli.h"

#include <algorithm>
#include <cstdlib>

#include "core/graph/PluginLoader.h"
#include "core/util/DidYouMean.h"
#include "passes/RegisterPasses.h"

namespace fovea::app {

void addCommands(CLI::App& app, CliOptions& o) {
    app.require_subcommand(1);
    app.set_version_flag("--version", FOVEA_VERSION);
    addRunCommand(app, o.run);
    addReferenceCommand(app, o.reference);
    addMergeCommand(app, o.merge);
    addValidateCommand(app, o.validate);
    addPassesCommand(app, o.passes);
    addCompareCommand(app, o.compare);
    addBenchCommand(app, o.bench);
    addInspectCommand(app, o.inspect);
    addGainCommand(app, o.gain);
    addDevicesCommand(app, o.devices);
    // Every subcommand knows the passes of a plugin (docs/plugins.md).
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
        sub->add_option("--plugin", o.plugins,
                        "load the pass types of this plugin library (repeatable; also "
                        "FOVEA_PLUGIN_PATH)")
            ->type_name("LIB.so");
}

std::string unknownSubcommand(CLI::App& app, int argc, const char* const* argv) {
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

int runSubcommand(const CLI::App& app, const CliOptions& o) {
    registerBuiltinPasses();
    std::vector<graph::PluginFile> plugins;
    for (const auto& p : o.plugins) plugins.push_back({p, "--plugin"});
    if (const char* path = std::getenv("FOVEA_PLUGIN_PATH"))
        for (auto& f : graph::pluginPathFiles(path)) plugins.push_back(std::move(f));
    (void)graph::loadPassPlugins(plugins, graph::passRegistry());
    if (app.got_subcommand("run")) return runCommand(o.run);
    if (app.got_subcommand("reference")) return referenceCommand(o.reference);
    if (app.got_subcommand("merge")) return mergeCommand(o.merge);
    if (app.got_subcommand("validate")) return validateCommand(o.validate);
    if (app.got_subcommand("passes")) return passesCommand(o.passes);
    if (app.got_subcommand("compare")) return compareCommand(o.compare);
    if (app.got_subcommand("bench")) return benchCommand(o.bench);
    if (app.got_subcommand("inspect")) return inspectCommand(o.inspect);
    if (app.got_subcommand("gain")) return gainCommand(o.gain);
    if (app.got_subcommand("devices")) return devicesCommand(o.devices);
    return kExitInput;
}

}  // namespace fovea::app
