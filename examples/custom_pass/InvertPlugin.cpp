// The same InvertPass as a plugin library: `fovea run invert.json --plugin ./fovea_invert.so`
// (docs/plugins.md). Its shader folder sits beside the library (CMakeLists.txt copies it there).
#include <memory>

#include "InvertPass.h"
#include "core/graph/PassPlugin.h"

FOVEA_PASS_PLUGIN(plugin) {
    const std::filesystem::path shaders = plugin.directory() / "shaders";
    plugin.registry.add({"Invert",
                         "white - color per channel, alpha kept (examples/custom_pass, a plugin)",
                         [shaders] { return std::make_unique<InvertPass>(shaders); }});
}
