// `fovea passes`: every pass type with its fields, formats and parameters (docs from the one
// ParamVisitor declaration).
#include <iostream>

#include "apps/fovea/Commands.h"
#include "apps/fovea/PassDocs.h"
#include "core/graph/PassRegistry.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"
#include "core/vk/Formats.h"

namespace fovea::app {

void addPassesCommand(CLI::App& app, PassesOptions& o) {
    auto* cmd = app.add_subcommand("passes", "list pass types, their fields and parameters");
    cmd->add_option("type", o.type, "show only this pass type");
    cmd->add_flag("--json", o.json, "machine-readable output");
    cmd->add_flag("--markdown", o.markdown,
                  "the field and parameter tables of docs/passes/<Type>.md, as generated");
    cmd->add_option("--update-docs", o.updateDocs,
                    "rewrite the generated tables in DIR/<Type>.md for every pass type");
    cmd->add_option("--check-docs", o.checkDocs,
                    "exit 1 naming every page of DIR whose generated tables are stale or missing");
    cmd->add_flag("--plugins-only", o.pluginsOnly,
                  "only the pass types of --plugin / FOVEA_PLUGIN_PATH (a plugin's own docs)");
}

namespace {

// "16 + 8 per pixel" style text of a buffer size rule.
std::string bufferRule(const graph::BufferSize& b) {
    std::string text = std::to_string(b.header) + " B";
    if (b.perPixel) text += " + " + std::to_string(b.perPixel) + " B per pixel";
    if (b.block)
        text += " + " + std::to_string(b.perBlock) + " B per " + std::to_string(b.block) + "x" +
                std::to_string(b.block) + " block" +
                (b.extraBlocks ? " (+" + std::to_string(b.extraBlocks) + " per axis)" : "");
    return text;
}

nlohmann::json describePass(const graph::PassTypeInfo& info, const std::string& origin) {
    auto pass = info.create();
    pass->setIdentity(info.type, info.type);
    graph::applyParamDefaults(*pass);
    graph::Reflection r;
    pass->reflect(r);
    nlohmann::json fields = nlohmann::json::array();
    for (const auto& f : r.fields()) {
        nlohmann::json jf = {
            {"name", f.name},
            {"kind", graph::fieldKindName(f.kind)},
            {"format", f.format != vk::Format::eUndefined ? gpu::formatName(f.format)
                       : f.floatOnly                      ? "any float"
                                                          : "any"},
            {"size", graph::sizeRuleName(f.size)},
            {"optional", f.optional},
            {"persistent", f.persistent},
            {"history", f.historyFrames},
            {"doc", f.doc}};
        if (f.size == graph::SizeRule::SameAsInput) jf["same_as"] = f.sameAs;
        if (f.size == graph::SizeRule::Scaled) jf["scale"] = f.scale;
        if (f.size == graph::SizeRule::Buffer) jf["buffer"] = bufferRule(f.buffer);
        fields.push_back(jf);
    }
    return {{"type", info.type},
            {"doc", info.doc},
            {"fields", fields},
            {"params", graph::describeParams(*pass)},
            {"scene_needs", graph::sceneFeatureNames(pass->sceneNeeds())},
            {"cacheable", pass->cacheable()},
            {"bypass", pass->bypass()},
            {"plugin", origin.empty() ? nlohmann::json() : nlohmann::json(origin)}};
}

}  // namespace

int passesCommand(const PassesOptions& o) {
    const auto& registry = graph::passRegistry();
    std::vector<std::string> types;
    for (const auto& t : registry.types())
        if (!o.pluginsOnly || !registry.origin(t).empty()) types.push_back(t);
    if (o.pluginsOnly && types.empty())
        throw InputError("fovea passes", "--plugins-only",
                         "no plugin is loaded (give --plugin LIB.so or set FOVEA_PLUGIN_PATH)");
    if (!o.type.empty()) {
        if (!registry.find(o.type))
            throw InputError("fovea passes", "",
                             "unknown pass type '" + o.type + "'" + didYouMean(o.type, types));
        types = {o.type};
    }
    nlohmann::json all = nlohmann::json::array();
    for (const auto& t : types) all.push_back(describePass(*registry.find(t), registry.origin(t)));
    if (!o.updateDocs.empty() || !o.checkDocs.empty()) {
        const bool write = !o.updateDocs.empty();
        const auto problems = syncPassDocs(write ? o.updateDocs : o.checkDocs, all, write);
        for (const auto& p : problems) std::cerr << "error: " << p << "\n";
        if (problems.empty())
            std::cout << "pass docs: " << all.size() << " pages " << (write ? "updated" : "current")
                      << "\n";
        return problems.empty() ? kExitOk : kExitRuntime;
    }
    if (o.markdown) {
        for (const auto& p : all)
            std::cout << "## " << p["type"].get<std::string>() << "\n\n### Fields\n\n"
                      << fieldsMarkdown(p) << "\n### Parameters\n\n"
                      << paramsMarkdown(p) << "\n";
        return kExitOk;
    }
    if (o.json) {
        std::cout << all.dump(2) << "\n";
        return kExitOk;
    }
    for (const auto& p : all) {
        std::cout << p["type"].get<std::string>() << " — " << p["doc"].get<std::string>()
                  << (p["plugin"].is_string() ? "  (plugin " + p["plugin"].get<std::string>() + ")"
                                              : "")
                  << "\n";
        for (const auto& f : p["fields"])
            std::cout << "    " << f["kind"].get<std::string>() << " "
                      << f["name"].get<std::string>() << "  [" << f["format"].get<std::string>()
                      << ", " << f["size"].get<std::string>()
                      << (f["optional"].get<bool>() ? ", optional" : "")
                      << (f["persistent"].get<bool>() ? ", persistent" : "")
                      << (f["history"].get<uint32_t>() > 0
                              ? ", keeps " + f["history"].dump() + " previous frame(s)"
                              : "")
                      << "]  " << f["doc"].get<std::string>() << "\n";
        for (const auto& q : p["params"]) {
            std::cout << "    param " << q["name"].get<std::string>() << " ("
                      << q["type"].get<std::string>() << ", default " << q["default"].dump();
            if (q.contains("min")) std::cout << ", min " << q["min"].dump();
            if (q.contains("max")) std::cout << ", max " << q["max"].dump();
            if (q.contains("choices")) std::cout << ", one of " << q["choices"].dump();
            std::cout << ")  " << q["doc"].get<std::string>() << "\n";
        }
        std::cout << "\n";
    }
    return kExitOk;
}

}  // namespace fovea::app
