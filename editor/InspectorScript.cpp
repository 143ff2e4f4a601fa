#include "editor/InspectorScript.h"

#include <fstream>
#include <map>
#include <sstream>

#include "core/util/DidYouMean.h"
#include "core/util/Error.h"
#include "core/util/UserFile.h"

namespace fovea::editor {

namespace {

// Command -> number of arguments.
const std::map<std::string, size_t>& commands() {
    static const std::map<std::string, size_t> kCommands{
        {"select", 1},     {"set", 2},         {"preview", 1},    {"channel", 1},
        {"exposure", 1},   {"falsecolour", 1}, {"gaze", 2},       {"pause", 0},
        {"resume", 0},     {"step", 0},        {"reset", 0},      {"reload", 1},
        {"screenshot", 1}, {"compare", 1},     {"difference", 1}, {"zoom", 3},
        {"camera", 1},     {"move", 3},        {"look", 2},       {"place", 3},
        {"saveas", 1},     {"previewshot", 1}, {"rebuild", 0}};
    return kCommands;
}

}  // namespace

std::vector<ScriptCommand> parseInspectorScript(const std::filesystem::path& path) {
    std::istringstream in(readUserTextFile(path, kMaxJsonFileBytes, "the script file"));
    std::vector<ScriptCommand> out;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        if (const size_t hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        std::istringstream words(line);
        std::string frame;
        if (!(words >> frame)) continue;  // blank or comment
        ScriptCommand cmd;
        cmd.where = path.string() + ":" + std::to_string(number);
        char* end = nullptr;
        const unsigned long f = std::strtoul(frame.c_str(), &end, 10);
        if (frame[0] == '-' || *end != '\0' || f > 1000000)
            throw InputError(cmd.where, "",
                             "expected a frame number (0..1000000), got '" + frame + "'");
        cmd.frame = uint32_t(f);
        if (!(words >> cmd.verb))
            throw InputError(cmd.where, "", "missing command after the frame");
        for (std::string a; words >> a;) cmd.args.push_back(a);
        auto it = commands().find(cmd.verb);
        if (it == commands().end()) {
            std::vector<std::string> names;
            for (const auto& [name, n] : commands()) names.push_back(name);
            throw InputError(cmd.where, "",
                             "unknown command '" + cmd.verb + "'" + didYouMean(cmd.verb, names));
        }
        if (cmd.args.size() != it->second)
            throw InputError(cmd.where, "",
                             "'" + cmd.verb + "' takes " + std::to_string(it->second) +
                                 " argument(s), got " + std::to_string(cmd.args.size()));
        out.push_back(std::move(cmd));
    }
    return out;
}

}  // namespace fovea::editor
