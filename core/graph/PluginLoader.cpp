#include "core/graph/PluginLoader.h"

#include <dlfcn.h>

#include <algorithm>
#include <fstream>
#include <set>

#include "core/graph/PassPlugin.h"
#include "core/util/Error.h"

namespace fovea::graph {

namespace fs = std::filesystem;

std::string pluginAbi() {
    return FOVEA_PLUGIN_ABI;
}

std::vector<PluginFile> pluginPathFiles(const std::string& value) {
    std::vector<PluginFile> files;
    size_t start = 0;
    while (start <= value.size()) {
        const size_t end = std::min(value.find(':', start), value.size());
        const std::string entry = value.substr(start, end - start);
        start = end + 1;
        if (entry.empty()) continue;
        std::error_code ec;
        if (fs::is_directory(entry, ec)) {
            std::vector<fs::path> found;
            for (const auto& e : fs::directory_iterator(entry, ec))
                if (e.path().extension() == ".so") found.push_back(e.path());
            std::sort(found.begin(), found.end());
            for (auto& f : found) files.push_back({f, "FOVEA_PLUGIN_PATH"});
        } else if (fs::exists(entry, ec)) {
            files.push_back({entry, "FOVEA_PLUGIN_PATH"});
        } else {
            throw InputError("FOVEA_PLUGIN_PATH", "",
                             "entry '" + entry + "' is neither a plugin file nor a folder");
        }
    }
    return files;
}

namespace {

// dlopen() maps any ELF it is given, and a text file gives a loader message about "invalid ELF
// header": name the problem plainly before the loader sees the file.
void checkSharedLibraryFile(const PluginFile& f) {
    const std::string file = f.path.string();
    std::error_code ec;
    if (!fs::exists(f.path, ec))
        throw InputError(file, "", "plugin not found (named by " + f.source + ")");
    if (!fs::is_regular_file(f.path, ec))
        throw InputError(file, "", "plugin is not a regular file (named by " + f.source + ")");
    char magic[4] = {};
    std::ifstream in(f.path, std::ios::binary);
    if (!in.read(magic, 4) || magic[0] != 0x7f || magic[1] != 'E' || magic[2] != 'L' ||
        magic[3] != 'F')
        throw InputError(file, "",
                         "not a shared library (no ELF header; named by " + f.source + ")");
}

template <class Fn>
Fn symbol(void* handle, const char* name, const std::string& file) {
    dlerror();
    void* address = dlsym(handle, name);
    if (!address)
        throw InputError(file, "",
                         std::string("not a fovea pass plugin: it defines no ") + name +
                             " (write the entry point with FOVEA_PASS_PLUGIN, "
                             "core/graph/PassPlugin.h)");
    return reinterpret_cast<Fn>(address);
}

// Runs the plugin's entry point on a staging registry: nothing of a refused plugin is kept.
PassRegistry registerFromPlugin(const fs::path& path) {
    const std::string file = path.string();
    // RTLD_NOW: an undefined symbol is reported here with its name, not as a crash at first
    // use. RTLD_LOCAL: two plugins' private symbols do not interpose on each other.
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
        const char* reason = dlerror();
        throw InputError(file, "",
                         std::string("cannot load plugin: ") + (reason ? reason : "unknown"));
    }
    using AbiFn = const char* (*)();
    using RegisterFn = void (*)(PluginContext&);
    const std::string abi = symbol<AbiFn>(handle, "fovea_plugin_abi", file)();
    if (abi != pluginAbi())
        throw InputError(file, "",
                         "plugin built against '" + abi + "', but this is '" + pluginAbi() +
                             "': rebuild it against this fovea's headers");
    const auto registerPasses = symbol<RegisterFn>(handle, "fovea_plugin_register", file);
    PassRegistry staging;
    PluginContext context{staging, path};
    try {
        registerPasses(context);
    } catch (const std::exception& e) {
        throw InputError(file, "", std::string("plugin registration failed: ") + e.what());
    } catch (...) {  // a plugin may throw anything; fovea never ends in std::terminate
        throw InputError(file, "", "plugin registration failed: a non-standard exception");
    }
    if (staging.types().empty()) throw InputError(file, "", "plugin registers no pass type");
    return staging;
}

}  // namespace

std::vector<std::string> loadPassPlugins(const std::vector<PluginFile>& files,
                                         PassRegistry& registry) {
    std::vector<std::string> added;
    std::set<fs::path> loaded;
    for (const PluginFile& f : files) {
        checkSharedLibraryFile(f);
        const fs::path path = fs::canonical(f.path);
        if (!loaded.insert(path).second) continue;
        PassRegistry staging = registerFromPlugin(path);
        for (const std::string& type : staging.types())
            if (registry.find(type)) {
                const std::string owner = registry.origin(type);
                throw InputError(path.string(), "",
                                 "plugin registers pass type '" + type +
                                     "', which already exists (" +
                                     (owner.empty() ? "built into fovea" : "from " + owner) + ")");
            }
        for (const std::string& type : staging.types()) {
            registry.add(*staging.find(type), path.string());
            added.push_back(type);
        }
    }
    return added;
}

}  // namespace fovea::graph
