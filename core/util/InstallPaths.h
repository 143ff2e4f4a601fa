// Where fovea finds the files it ships (docs/install.md): the GLSL shaders it compiles at run time
// and the graphs its commands default to (graphs/reference.json). The same binary works from its
// build tree and installed (bin/fovea with share/fovea/ beside it), and keeps working when the
// source tree it was built from is moved or deleted after install.
#pragma once
#include <filesystem>
#include <string>

namespace fovea {

// The folder of the running executable (/proc/self/exe); empty when it cannot be read.
std::filesystem::path executableDir();

// The shader folder, first match of: $FOVEA_SHADER_DIR (when set and not empty: used as given,
// even when missing, so a wrong value is an error and not silently replaced); <exe>/../share/
// fovea/shaders (an install; share = CMAKE_INSTALL_DATADIR); the source tree's shaders/ (a build
// tree). A folder counts when it has common/ (an emptied source tree does not). Throws
// RuntimeError naming every folder it looked in when none does.
std::filesystem::path shaderRoot();

// The folder holding graphs/ (and graphs/cameras/): <exe>/../share/fovea when installed, else the
// source tree (also when that is gone: a graph named from it is then reported missing).
std::filesystem::path dataRoot();

// dataRoot() / "graphs" / name, e.g. shippedGraph("reference.json").
std::string shippedGraph(const std::string& name);

}  // namespace fovea
