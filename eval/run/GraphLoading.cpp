#include "eval/run/GraphLoading.h"

#include <regex>

#include "core/graph/PassRegistry.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"

namespace fovea::eval {

std::array<uint32_t, 2> parseSize(const std::string& text, const std::string& flag) {
    static const std::regex kPattern(R"((\d{1,5})x(\d{1,5}))");
    std::smatch m;
    if (!std::regex_match(text, m, kPattern))
        throw InputError(flag, "", "expected WIDTHxHEIGHT (e.g. 256x256), got '" + text + "'");
    uint32_t w = uint32_t(std::stoul(m[1])), h = uint32_t(std::stoul(m[2]));
    if (w < 1 || h < 1 || w > 16384 || h > 16384)
        throw InputError(flag, "", "size out of range: " + text + " (allowed 1..16384 per axis)");
    return {w, h};
}

std::array<uint32_t, 2> renderSize(const GraphOptions& options, const graph::GraphDesc& desc) {
    if (!options.size.empty()) return parseSize(options.size, "--size");
    if (desc.defaults.size) return *desc.defaults.size;
    return {256, 256};
}

graph::GraphDesc loadGraph(const GraphOptions& options) {
    graph::GraphDesc desc = graph::parseGraphFile(options.graph);
    const auto& registry = graph::passRegistry();
    for (const std::string& set : options.sets) {
        const std::string flag = "--set " + set;
        auto eq = set.find('=');
        auto dot = set.find('.');
        if (eq == std::string::npos || dot == std::string::npos || dot > eq)
            throw InputError(flag, "", "expected pass.param=value");
        std::string passName = set.substr(0, dot);
        std::string param = set.substr(dot + 1, eq - dot - 1);
        std::string value = set.substr(eq + 1);
        graph::PassDesc* target = nullptr;
        for (auto& p : desc.passes)
            if (p.name == passName) target = &p;
        if (!target)
            throw InputError(
                flag, "",
                "graph has no pass '" + passName + "'" + didYouMean(passName, desc.passNames()));
        if (!registry.find(target->type)) continue;  // reported with its pointer at compile
        auto pass = registry.create(target->type, target->name);
        target->params[param] = graph::parseParamText(*pass, param, value, flag);
        // Validate now so a bad value is reported against the flag, not the graph file.
        graph::loadParams(*pass, nlohmann::json{{param, target->params[param]}}, flag, "");
    }
    return desc;
}

}  // namespace fovea::eval
