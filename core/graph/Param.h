// Pass parameters, declared once. A pass lists each parameter exactly once in
// `Pass::params(ParamVisitor&)`: name, type, default, range/choices and doc. The default lives
// only there: the member is value-initialized (`float mAlpha{};`) and PassRegistry::create
// applies the declared default. Visitors turn that one
// declaration into defaults, JSON load (with file + JSON-pointer errors), JSON save, the
// `fovea passes` listing, and later the ImGui panel.
#pragma once
#include <glm/glm.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fovea::graph {

struct ParamRange {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
};

struct ParamSpec {
    std::string name;
    std::string doc;
    ParamRange range;
    std::vector<std::string> choices;  // for string parameters: the allowed values (empty = any)
    // A file path: relative values from a graph file are resolved against the graph file's folder
    // (CompileContext::resolvePath); relative values from `--set` against the working directory.
    bool path = false;
};

class ParamVisitor {
public:
    virtual ~ParamVisitor() = default;

    // The typed hooks a visitor implements. `value` is the pass member, `def` its default.
    virtual void visit(const ParamSpec& spec, bool& value, bool def) = 0;
    virtual void visit(const ParamSpec& spec, int& value, int def) = 0;
    virtual void visit(const ParamSpec& spec, float& value, float def) = 0;
    virtual void visit(const ParamSpec& spec, std::string& value, const std::string& def) = 0;
    virtual void visit(const ParamSpec& spec, glm::vec3& value, const glm::vec3& def) = 0;

    // What pass authors call.
    void add(const std::string& name, bool& value, bool def, const std::string& doc) {
        visit(ParamSpec{name, doc, {}, {}}, value, def);
    }
    void add(const std::string& name, int& value, int def, const std::string& doc,
             ParamRange range = {}) {
        visit(ParamSpec{name, doc, range, {}}, value, def);
    }
    void add(const std::string& name, float& value, float def, const std::string& doc,
             ParamRange range = {}) {
        visit(ParamSpec{name, doc, range, {}}, value, def);
    }
    void add(const std::string& name, std::string& value, const std::string& def,
             const std::string& doc, std::vector<std::string> choices = {}) {
        visit(ParamSpec{name, doc, {}, std::move(choices)}, value, def);
    }
    // A file-path string parameter (see ParamSpec::path).
    void addPath(const std::string& name, std::string& value, const std::string& def,
                 const std::string& doc) {
        visit(ParamSpec{name, doc, {}, {}, true}, value, def);
    }
    void add(const std::string& name, glm::vec3& value, const glm::vec3& def,
             const std::string& doc, ParamRange range = {}) {
        visit(ParamSpec{name, doc, range, {}}, value, def);
    }
};

class Pass;

// Sets every parameter to its declared default.
void applyParamDefaults(Pass& pass);

// Loads `params` (a JSON object) into the pass. Errors name `file` and `pointer` + "/name":
// unknown parameter (did you mean), wrong type, out of range, not one of the choices.
void loadParams(Pass& pass, const nlohmann::json& params, const std::string& file,
                const std::string& pointer);

// Current values as a JSON object; `onlyChanged` omits parameters equal to their default.
nlohmann::json saveParams(Pass& pass, bool onlyChanged);

// [{name, type, default, min?, max?, choices?, doc}] for `fovea passes` and docs.
nlohmann::json describeParams(Pass& pass);

// Converts the text of a `--set pass.param=value` to JSON of the parameter's declared type
// (so `--set tm.exposure=2` is a number and `--set src.pattern=noise` a string). A relative
// path parameter (ParamSpec::path) is made absolute from the working directory: the user typed
// it there, while the graph file's own paths are relative to its folder.
nlohmann::json parseParamText(Pass& pass, const std::string& param, const std::string& text,
                              const std::string& flag);

}  // namespace fovea::graph
