// Loads pass plugins (core/graph/PassPlugin.h) into a registry: the files named by `--plugin` and
// by FOVEA_PLUGIN_PATH. Every refusal is an InputError naming the file: missing, not a shared
// library, unloadable (with the loader's reason, e.g. an undefined symbol), not a fovea plugin,
// built against another fovea ABI, or registering a type that already exists.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "core/graph/PassRegistry.h"

namespace fovea::graph {

struct PluginFile {
    std::filesystem::path path;
    std::string source;  // how the user named it: "--plugin" or "FOVEA_PLUGIN_PATH"
};

// The files of a FOVEA_PLUGIN_PATH value: ':'-separated entries, each a plugin file or a folder
// whose "*.so" files are taken in name order. Empty entries are skipped; a missing entry is an
// InputError naming it.
std::vector<PluginFile> pluginPathFiles(const std::string& value);

// Loads each file once (by canonical path) and adds its types to `registry` with the file as
// their origin; all of a plugin's types or none. Returns the types added, in order. A loaded
// library stays loaded until the process exits: its code backs the registry's factories.
std::vector<std::string> loadPassPlugins(const std::vector<PluginFile>& files,
                                         PassRegistry& registry);

// This fovea's plugin ABI string (FOVEA_PLUGIN_ABI as compiled into core).
std::string pluginAbi();

}  // namespace fovea::graph
