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
    // A type that no longer exists, with what replaces it: a graph naming it gets this hint in
    // its "unknown pass type" error (e.g. a type split in two).
    void retire(const std::string& type, std::string replacement);
    std::string retiredHint(const std::string& type) const;  // "" unless retired
    // Creates a pass with default parameters and its identity set.
    std::unique_ptr<Pass> create(const std::string& type, const std::string& name) const;

private:
    struct Entry {
        PassTypeInfo info;
        std::string origin;
    };
    std::map<std::string, Entry> mTypes;
    std::map<std::string, std::string> mRetired;
};

PassRegistry& passRegistry();

}  // namespace fovea::graph
