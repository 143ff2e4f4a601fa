#include "apps/fovea/PassDocs.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/util/Error.h"

namespace fovea::app {

namespace {

constexpr const char* kFieldsBegin =
    "<!-- BEGIN generated fields: fovea passes --update-docs docs/passes -->";
constexpr const char* kFieldsEnd = "<!-- END generated fields -->";
constexpr const char* kParamsBegin =
    "<!-- BEGIN generated parameters: fovea passes --update-docs docs/passes -->";
constexpr const char* kParamsEnd = "<!-- END generated parameters -->";

// A table cell: pipes escaped, line breaks flattened.
std::string cell(std::string text) {
    std::string out;
    for (char c : text) {
        if (c == '|')
            out += "\\|";
        else if (c == '\n')
            out += ' ';
        else
            out += c;
    }
    return out;
}

std::string code(const std::string& text) {
    return "`" + text + "`";
}

std::string jsonText(const nlohmann::json& v) {
    if (v.is_string()) return v.get<std::string>();
    if (v.is_number_float()) {
        std::ostringstream s;
        s << v.get<double>();
        return s.str();
    }
    return v.dump();
}

std::string replaceBlock(const std::string& page, const char* begin, const char* end,
                         const std::string& body, const std::string& file) {
    size_t b = page.find(begin);
    size_t e = b == std::string::npos ? b : page.find(end, b);
    if (b == std::string::npos || e == std::string::npos)
        throw InputError(file, "",
                         std::string("missing the marker pair '") + begin + "' ... '" + end + "'");
    b += std::string(begin).size();
    return page.substr(0, b) + "\n" + body + page.substr(e);
}

}  // namespace

std::string fieldsMarkdown(const nlohmann::json& pass) {
    std::ostringstream s;
    s << "| Field | Kind | Format | Size | Documentation |\n|---|---|---|---|---|\n";
    for (const auto& f : pass["fields"]) {
        std::string kind = f["kind"].get<std::string>();
        if (f["optional"].get<bool>()) kind += ", optional";
        if (f["persistent"].get<bool>()) kind += ", persistent";
        if (f.value("history", 0u) > 0)
            kind += ", keeps " + std::to_string(f["history"].get<uint32_t>()) + " previous frame" +
                    (f["history"].get<uint32_t>() > 1 ? "s" : "") + " (`prev_" +
                    f["name"].get<std::string>() + "`)";
        std::string size = f["size"].get<std::string>();
        if (f.contains("same_as")) size += " " + code(f["same_as"].get<std::string>());
        if (f.contains("scale")) size += " × " + jsonText(f["scale"]);
        if (f.contains("buffer")) size += ": " + f["buffer"].get<std::string>();
        s << "| " << code(f["name"].get<std::string>()) << " | " << kind << " | "
          << f["format"].get<std::string>() << " | " << cell(size) << " | "
          << cell(f["doc"].get<std::string>()) << " |\n";
    }
    return s.str();
}

std::string paramsMarkdown(const nlohmann::json& pass) {
    if (pass["params"].empty()) return "No parameters.\n";
    std::ostringstream s;
    s << "| Name | Type | Default | Range / choices | Documentation |\n|---|---|---|---|---|\n";
    for (const auto& p : pass["params"]) {
        std::string range;
        if (p.contains("min") || p.contains("max"))
            range = (p.contains("min") ? jsonText(p["min"]) : "") + " .. " +
                    (p.contains("max") ? jsonText(p["max"]) : "");
        if (p.contains("choices"))
            for (const auto& c : p["choices"])
                range += (range.empty() ? "" : ", ") + code(jsonText(c));
        s << "| " << code(p["name"].get<std::string>()) << " | " << p["type"].get<std::string>()
          << " | " << code(jsonText(p["default"])) << " | " << cell(range) << " | "
          << cell(p["doc"].get<std::string>()) << " |\n";
    }
    return s.str();
}

std::string updatePassPage(const std::string& page, const nlohmann::json& pass,
                           const std::string& file) {
    std::string out = replaceBlock(page, kFieldsBegin, kFieldsEnd, fieldsMarkdown(pass), file);
    return replaceBlock(out, kParamsBegin, kParamsEnd, paramsMarkdown(pass), file);
}

std::vector<std::string> syncPassDocs(const std::string& dir, const nlohmann::json& passes,
                                      bool write) {
    std::vector<std::string> problems;
    for (const auto& pass : passes) {
        const std::string file =
            (std::filesystem::path(dir) / (pass["type"].get<std::string>() + ".md")).string();
        std::ifstream in(file, std::ios::binary);
        std::ostringstream text;
        if (in) {
            text << in.rdbuf();
        } else if (write && !std::filesystem::exists(file)) {
            // A new type (e.g. a plugin's): a starter page around the generated tables.
            text << "# " << pass["type"].get<std::string>() << "\n\n"
                 << pass["doc"].get<std::string>() << "\n\n## Fields\n\n"
                 << kFieldsBegin << "\n"
                 << kFieldsEnd << "\n\n## Parameters\n\n"
                 << kParamsBegin << "\n"
                 << kParamsEnd << "\n";
        } else {
            problems.push_back(file + ": missing (every registered pass type has a page)");
            continue;
        }
        std::string updated;
        try {
            updated = updatePassPage(text.str(), pass, file);
        } catch (const InputError& e) {
            problems.push_back(e.what());
            continue;
        }
        if (updated == text.str()) continue;
        if (!write) {
            problems.push_back(file + ": generated tables differ from `fovea passes --markdown " +
                               pass["type"].get<std::string>() + "`");
            continue;
        }
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out << updated;
        if (!out.flush()) problems.push_back(file + ": cannot write");
    }
    return problems;
}

}  // namespace fovea::app
