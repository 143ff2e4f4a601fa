#include "core/graph/PassRegistry.h"

#include <stdexcept>

namespace fovea::graph {

void PassRegistry::add(PassTypeInfo info) {
    std::string type = info.type;
    mTypes[type] = std::move(info);
}

const PassTypeInfo* PassRegistry::find(const std::string& type) const {
    auto it = mTypes.find(type);
    return it == mTypes.end() ? nullptr : &it->second;
}

std::vector<std::string> PassRegistry::types() const {
    std::vector<std::string> out;
    for (const auto& [type, info] : mTypes) out.push_back(type);
    return out;
}

std::unique_ptr<Pass> PassRegistry::create(const std::string& type, const std::string& name) const {
    const PassTypeInfo* info = find(type);
    if (!info) throw std::logic_error("unknown pass type " + type);
    std::unique_ptr<Pass> pass = info->create();
    pass->setIdentity(name, type);
    applyParamDefaults(*pass);
    return pass;
}

PassRegistry& passRegistry() {
    static PassRegistry registry;
    return registry;
}

}  // namespace fovea::graph
