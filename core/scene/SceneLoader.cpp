#include "core/scene/SceneLoader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/scene/BuiltinScenes.h"
#include "core/scene/gltf/GltfLoader.h"
#include "core/util/Error.h"
#include "core/util/UserFile.h"

namespace fovea::scene {

Scene loadScene(const std::string& spec, bool allowExternalUris) {
    if (spec.rfind("builtin:", 0) == 0) return loadBuiltinScene(spec);
    if (spec.empty())
        throw InputError("", "", "no scene given (a .gltf/.glb path or builtin:<name>)");
    std::filesystem::path path(spec);
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (extension != ".gltf" && extension != ".glb") {
        std::string names;
        for (const std::string& n : builtinSceneNames()) names += ", " + n;
        throw InputError(spec, "",
                         "unsupported scene file type '" + extension +
                             "' (expected .gltf, .glb or one of the built-in scenes" + names + ")");
    }
    if (const std::string problem = regularFileProblem(path); !problem.empty())
        throw InputError(
            spec, "",
            problem == "file not found" ? problem : "not a regular file (" + problem + ")");
    GltfLoadOptions options;
    options.allowExternalUris = allowExternalUris;
    return loadGltf(path, options);
}

}  // namespace fovea::scene
