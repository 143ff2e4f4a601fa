// The one global of fovea: the table of pass types. Filled explicitly by
// registerBuiltinPasses() (passes/RegisterPasses.h); core never names a concrete pass.
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
    void add(PassTypeInfo info);
    const PassTypeInfo* find(const std::string& type) const;
    std::vector<std::string> types() const;  // sorted
    // Creates a pass with default parameters and its identity set.
    std::unique_ptr<Pass> create(const std::string& type, const std::string& name) const;

private:
    std::map<std::string, PassTypeInfo> mTypes;
};

PassRegistry& passRegistry();

}  // namespace fovea::graph
