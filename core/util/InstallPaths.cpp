#include "core/util/InstallPaths.h"

#include <cstdlib>

#include "core/util/Error.h"

namespace fovea {

namespace fs = std::filesystem;

fs::path executableDir() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::path() : exe.parent_path();
}

namespace {

// <exe>/../share/fovea: the layout `cmake --install` writes (CMakeLists.txt, install rules; the
// executable in <prefix>/bin, the data in <prefix>/<CMAKE_INSTALL_DATADIR>/fovea).
fs::path installedShare() {
    const fs::path dir = executableDir();
    return dir.empty() ? fs::path() : (dir.parent_path() / FOVEA_INSTALL_SHARE).lexically_normal();
}

bool isDir(const fs::path& p) {
    std::error_code ec;
    return !p.empty() && fs::is_directory(p, ec);
}

// A shader folder is one with common/ in it (the GLSL every pass includes), not merely a folder of
// that name: an emptied or replaced source tree does not count.
bool isShaderDir(const fs::path& p) {
    return isDir(p) && isDir(p / "common");
}

}  // namespace

fs::path shaderRoot() {
    if (const char* env = std::getenv("FOVEA_SHADER_DIR"); env && *env) {
        if (!isShaderDir(env))
            throw RuntimeError(std::string("shader folder '") + env +
                               "' (from FOVEA_SHADER_DIR) does not exist or has no common/");
        return env;
    }
    const fs::path installed = installedShare() / "shaders";
    if (isShaderDir(installed)) return installed;
    const fs::path source = FOVEA_SHADER_DIR;
    if (isShaderDir(source)) return source;
    throw RuntimeError("no shader folder: looked in '" + installed.string() +
                       "' (an install) and '" + source.string() +
                       "' (the source tree this fovea was built from); reinstall fovea or set "
                       "FOVEA_SHADER_DIR");
}

fs::path dataRoot() {
    // Not an error when neither exists: the graph named from it is then reported missing with
    // its path, like any graph file.
    const fs::path installed = installedShare();
    return isDir(installed / "graphs") ? installed : fs::path(FOVEA_SOURCE_DIR);
}

std::string shippedGraph(const std::string& name) {
    return (dataRoot() / "graphs" / name).string();
}

}  // namespace fovea
