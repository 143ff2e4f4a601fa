#include "core/graph/Param.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <sstream>

#include "core/graph/Pass.h"
#include "core/util/DidYouMean.h"
#include "core/util/Error.h"

namespace fovea::graph {
namespace {

using nlohmann::json;

std::string jsonTypeName(const json& v) {
    if (v.is_boolean()) return "boolean";
    if (v.is_number_integer()) return "integer";
    if (v.is_number()) return "number";
    if (v.is_string()) return "string";
    if (v.is_array()) return "array";
    if (v.is_object()) return "object";
    return "null";
}

std::string formatNumber(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

class DefaultsVisitor : public ParamVisitor {
public:
    void visit(const ParamSpec&, bool& v, bool d) override { v = d; }
    void visit(const ParamSpec&, int& v, int d) override { v = d; }
    void visit(const ParamSpec&, float& v, float d) override { v = d; }
    void visit(const ParamSpec&, std::string& v, const std::string& d) override { v = d; }
    void visit(const ParamSpec&, glm::vec3& v, const glm::vec3& d) override { v = d; }
};

// Loads values from a JSON object, checking type, range and choices; every error names the file
// and the parameter's JSON pointer.
class LoadVisitor : public ParamVisitor {
public:
    LoadVisitor(const json& params, std::string file, std::string pointer)
        : mParams(params), mFile(std::move(file)), mPointer(std::move(pointer)) {}

    void visit(const ParamSpec& s, bool& v, bool) override {
        if (const json* j = take(s.name)) {
            if (!j->is_boolean()) fail(s.name, "expected a boolean, got " + describe(*j));
            v = j->get<bool>();
        }
    }
    void visit(const ParamSpec& s, int& v, int) override {
        if (const json* j = take(s.name)) {
            if (!j->is_number_integer()) fail(s.name, "expected an integer, got " + describe(*j));
            // Compare as double first so values beyond int range are reported, not wrapped.
            double d = j->get<double>();
            checkRange(s, d);
            checkLimits(s, d, double(std::numeric_limits<int>::min()),
                        double(std::numeric_limits<int>::max()));
            v = j->get<int>();
        }
    }
    void visit(const ParamSpec& s, float& v, float) override {
        if (const json* j = take(s.name)) {
            if (!j->is_number()) fail(s.name, "expected a number, got " + describe(*j));
            double d = j->get<double>();
            if (!std::isfinite(d)) fail(s.name, "expected a finite number");
            checkRange(s, d);
            checkLimits(s, d, -double(std::numeric_limits<float>::max()),
                        double(std::numeric_limits<float>::max()));
            v = static_cast<float>(d);
        }
    }
    void visit(const ParamSpec& s, std::string& v, const std::string&) override {
        if (const json* j = take(s.name)) {
            if (!j->is_string()) fail(s.name, "expected a string, got " + describe(*j));
            std::string value = j->get<std::string>();
            if (!s.choices.empty() &&
                std::find(s.choices.begin(), s.choices.end(), value) == s.choices.end()) {
                std::string list;
                for (const auto& c : s.choices) list += (list.empty() ? "" : ", ") + c;
                fail(s.name,
                     "'" + value + "' is not one of: " + list + didYouMean(value, s.choices));
            }
            v = value;
        }
    }
    void visit(const ParamSpec& s, glm::vec3& v, const glm::vec3&) override {
        if (const json* j = take(s.name)) {
            if (!j->is_array() || j->size() != 3)
                fail(s.name, "expected an array of 3 numbers, got " + describe(*j));
            glm::vec3 out;
            for (int i = 0; i < 3; ++i) {
                if (!(*j)[i].is_number())
                    fail(s.name + "/" + std::to_string(i),
                         "expected a number, got " + describe((*j)[i]));
                double d = (*j)[i].get<double>();
                if (!std::isfinite(d)) fail(s.name, "expected finite numbers");
                checkRange(s, d);
                checkLimits(s, d, -double(std::numeric_limits<float>::max()),
                            double(std::numeric_limits<float>::max()));
                out[i] = static_cast<float>(d);
            }
            v = out;
        }
    }

    // Keys of the JSON object that no declared parameter consumed.
    void checkUnknown() const {
        for (const auto& [key, value] : mParams.items()) {
            if (mSeen.count(key)) continue;
            std::string hint = didYouMean(key, mDeclared);
            std::string list;
            for (const auto& d : mDeclared) list += (list.empty() ? "" : ", ") + d;
            throw InputError(
                mFile, mPointer + "/" + key,
                "unknown parameter '" + key + "'" + hint +
                    (hint.empty() ? " (parameters: " + (list.empty() ? "none" : list) + ")" : ""));
        }
    }

private:
    const json* take(const std::string& name) {
        mDeclared.push_back(name);
        if (!mParams.is_object() || !mParams.contains(name)) return nullptr;
        mSeen.insert(name);
        return &mParams.at(name);
    }
    static std::string describe(const json& j) {
        std::string text = j.dump();
        if (text.size() > 40) text = text.substr(0, 37) + "...";
        return jsonTypeName(j) + " " + text;
    }
    void checkRange(const ParamSpec& s, double d) const {
        if (d < s.range.min || d > s.range.max)
            fail(s.name, "out of range: " + formatNumber(d) + " (allowed " +
                             formatNumber(s.range.min) + ".." + formatNumber(s.range.max) + ")");
    }
    // The representable range of the C++ type, for parameters that declare no tighter range:
    // a value that would wrap (int) or become infinite (float) must not load silently.
    void checkLimits(const ParamSpec& s, double d, double lo, double hi) const {
        if (d < lo || d > hi)
            fail(s.name, "out of range: " + formatNumber(d) + " (allowed " + formatNumber(lo) +
                             ".." + formatNumber(hi) + ")");
    }
    [[noreturn]] void fail(const std::string& name, const std::string& message) const {
        throw InputError(mFile, mPointer + "/" + name, message);
    }

    const json& mParams;
    std::string mFile, mPointer;
    std::set<std::string> mSeen;
    std::vector<std::string> mDeclared;
};

class SaveVisitor : public ParamVisitor {
public:
    explicit SaveVisitor(bool onlyChanged) : mOnlyChanged(onlyChanged) {}
    json result = json::object();

    void visit(const ParamSpec& s, bool& v, bool d) override { put(s, v, v == d); }
    void visit(const ParamSpec& s, int& v, int d) override { put(s, v, v == d); }
    void visit(const ParamSpec& s, float& v, float d) override { put(s, v, v == d); }
    void visit(const ParamSpec& s, std::string& v, const std::string& d) override {
        put(s, v, v == d);
    }
    void visit(const ParamSpec& s, glm::vec3& v, const glm::vec3& d) override {
        put(s, json::array({v.x, v.y, v.z}), v == d);
    }

private:
    void put(const ParamSpec& s, const json& value, bool isDefault) {
        if (!(mOnlyChanged && isDefault)) result[s.name] = value;
    }
    bool mOnlyChanged;
};

class DescribeVisitor : public ParamVisitor {
public:
    json result = json::array();

    void visit(const ParamSpec& s, bool&, bool d) override { put(s, "bool", d); }
    void visit(const ParamSpec& s, int&, int d) override { put(s, "int", d); }
    void visit(const ParamSpec& s, float&, float d) override { put(s, "float", d); }
    void visit(const ParamSpec& s, std::string&, const std::string& d) override {
        put(s, "string", d);
    }
    void visit(const ParamSpec& s, glm::vec3&, const glm::vec3& d) override {
        put(s, "vec3", json::array({d.x, d.y, d.z}));
    }

private:
    void put(const ParamSpec& s, const char* type, const json& def) {
        json p = {{"name", s.name}, {"type", type}, {"default", def}, {"doc", s.doc}};
        if (std::isfinite(s.range.min)) p["min"] = s.range.min;
        if (std::isfinite(s.range.max)) p["max"] = s.range.max;
        if (!s.choices.empty()) p["choices"] = s.choices;
        if (s.path) p["path"] = true;
        result.push_back(p);
    }
};

}  // namespace

void applyParamDefaults(Pass& pass) {
    DefaultsVisitor v;
    pass.params(v);
}

void loadParams(Pass& pass, const nlohmann::json& params, const std::string& file,
                const std::string& pointer) {
    if (!params.is_object())
        throw InputError(file, pointer,
                         "expected an object of parameters, got " + jsonTypeName(params));
    LoadVisitor v(params, file, pointer);
    pass.params(v);
    v.checkUnknown();
}

nlohmann::json saveParams(Pass& pass, bool onlyChanged) {
    SaveVisitor v(onlyChanged);
    pass.params(v);
    return v.result;
}

nlohmann::json describeParams(Pass& pass) {
    DescribeVisitor v;
    pass.params(v);
    return v.result;
}

nlohmann::json parseParamText(Pass& pass, const std::string& param, const std::string& text,
                              const std::string& flag) {
    std::string type;
    bool path = false;
    std::vector<std::string> names;
    for (const auto& p : describeParams(pass)) {
        names.push_back(p["name"]);
        if (p["name"] == param) {
            type = p["type"];
            path = p.contains("path");
        }
    }
    if (type.empty())
        throw InputError(flag, "",
                         "pass '" + pass.name() + "' (" + pass.type() + ") has no parameter '" +
                             param + "'" + didYouMean(param, names));
    if (type == "string" && path && !text.empty() && std::filesystem::path(text).is_relative())
        return (std::filesystem::current_path() / text).lexically_normal().string();
    if (type == "string") return text;
    // Numbers, booleans and vectors are written as JSON ("2", "true", "[1,0,0]"); a parse
    // failure is reported against the flag, and the type check happens in loadParams.
    json value = json::parse(text, nullptr, false);
    if (value.is_discarded())
        throw InputError(flag, "", "cannot parse '" + text + "' as a " + type + " value");
    return value;
}

}  // namespace fovea::graph
