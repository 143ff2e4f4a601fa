// The one global of fovea: the table of pass types. Filled explicitly by
// registerBuiltinPasses() (passes/RegisterPasses.h) and by pass plugins (core/graph/PassPlugin.h,
// loaded by core/graph/PluginLoader.h); core never names a concrete pass.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/graph/Pass.h"

namespace fovea::graph {

struct PassTypeInfo {
    std::string type;
    std::string doc;  // one paragraph: what the pass does, with the document citation
    std::function<std::unique_ptr<Pass>()> create;
};

class PassRegistry {
public:
    // Adds a type. A type registered twice is a programming error (std::logic_error): a silent
    // replacement would run another pass than the one the graph's author knows by that name.
    // `origin`: "" for fovea's own types, else the plugin library that registered it.
    void add(PassTypeInfo info, std::string origin = "");
    const PassTypeInfo* find(const std::string& type) const;
    std::vector<std::string> types() const;  // sorted
    // "" for a built-in type, else the plugin file that registered it.
    std::string origin(const std::string& type) const;
    // Creates a pass with default parameters and its identity set.
    std::unique_ptr<Pass> create(const std::string& type, const std::string& name) const;

private:
    struct Entry {
        PassTypeInfo info;
        std::string origin;
    };
    std::map<std::string, Entry> mTypes;
};

PassRegistry& passRegistry();

}  // namespace fovea::graph
