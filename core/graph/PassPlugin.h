// Writing a pass library that `fovea` loads (`--plugin lib.so`, FOVEA_PLUGIN_PATH;
// docs/plugins.md). A plugin is a shared library compiled against fovea's installed headers (CMake:
// link fovea::plugin) that defines its entry point with FOVEA_PASS_PLUGIN:
//
//     #include "core/graph/PassPlugin.h"
//     FOVEA_PASS_PLUGIN(plugin) {
//         const auto shaders = plugin.directory() / "shaders";
//         plugin.registry.add({"Invert", "white - color",
//                              [shaders] { return std::make_unique<InvertPass>(shaders); }});
//     }
//
// The plugin's undefined fovea symbols resolve against the `fovea` executable, which exports
// them; so a plugin links no fovea library (it would bring a second pass registry). Before any
// plugin code runs past its static constructors, fovea compares FOVEA_PLUGIN_ABI as compiled into
// the plugin with its own and refuses another (core/graph/PluginLoader.h).
#pragma once
#include <filesystem>

#include "core/graph/PassRegistry.h"

// Bumped by hand whenever a header a plugin compiles against changes layout or a virtual
// signature (Pass, Reflection, ParamVisitor, the contexts); with fovea's version it names the ABI.
#define FOVEA_PLUGIN_ABI_REVISION "2"
#define FOVEA_PLUGIN_ABI_STRINGIFY2(x) #x
#define FOVEA_PLUGIN_ABI_STRINGIFY(x) FOVEA_PLUGIN_ABI_STRINGIFY2(x)
// std::string's layout differs between libstdc++'s two ABIs: part of the check.
#define FOVEA_PLUGIN_ABI                                            \
    "fovea " FOVEA_VERSION " plugin-abi " FOVEA_PLUGIN_ABI_REVISION \
    " cxx11-abi " FOVEA_PLUGIN_ABI_STRINGIFY(_GLIBCXX_USE_CXX11_ABI)

namespace fovea::graph {

// What a plugin's entry point receives.
struct PluginContext {
    PassRegistry& registry;         // add the plugin's pass types here (a staging registry)
    std::filesystem::path library;  // the plugin file as loaded (absolute)
    // The folder holding the plugin: where its own shader folder is expected.
    std::filesystem::path directory() const { return library.parent_path(); }
};

}  // namespace fovea::graph

// The two symbols fovea looks up. C linkage: unmangled names, the same from gcc and clang.
#define FOVEA_PASS_PLUGIN(contextName)                                                 \
    extern "C" __attribute__((visibility("default"))) const char* fovea_plugin_abi() { \
        return FOVEA_PLUGIN_ABI;                                                       \
    }                                                                                  \
    extern "C" __attribute__((visibility("default"))) void fovea_plugin_register(      \
        fovea::graph::PluginContext& contextName)
