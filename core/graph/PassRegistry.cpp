#include "core/graph/PassRegistry.h"

#include <stdexcept>

namespace fovea::graph {

void PassRegistry::add(PassTypeInfo info, std::string origin) {
    if (info.type.empty() || !info.create)
        throw std::logic_error("pass type registered without a name or a factory");
    std::string type = info.type;
    if (mTypes.count(type)) throw std::logic_error("pass type '" + type + "' registered twice");
    mTypes.emplace(type, Entry{std::move(info), std::move(origin)});
}

const PassTypeInfo* PassRegistry::find(const std::string& type) const {
    auto it = mTypes.find(type);
    return it == mTypes.end() ? nullptr : &it->second.info;
}

std::vector<std::string> PassRegistry::types() const {
    std::vector<std::string> out;
    for (const auto& [type, entry] : mTypes) out.push_back(type);
    return out;
}

void PassRegistry::retire(const std::string& type, std::string replacement) {
    mRetired[type] = std::move(replacement);
}

std::string PassRegistry::retiredHint(const std::string& type) const {
    auto it = mRetired.find(type);
    return it == mRetired.end() ? std::string() : it->second;
}

std::string PassRegistry::origin(const std::string& type) const {
    auto it = mTypes.find(type);
    return it == mTypes.end() ? std::string() : it->second.origin;
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
