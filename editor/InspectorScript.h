// `fovea inspect --script FILE`: what a user would do with the mouse, as lines of text, for
// tests and reproducible screenshots. Each line is "<frame> <command> [arguments]", run before
// that frame (0-based); '#' starts a comment. Commands:
//   select PASS                 select a pass (its parameters appear in the panel)
//   set PASS.PARAM VALUE        change a parameter (parsed by its declared type); rebuilds
//   preview PASS.FIELD          show a field in the preview
//   channel rgb|r|g|b|a|luminance,  exposure STOPS,  falsecolour on|off
//   gaze X Y                    gaze at (X, Y) in [0,1]^2 of the whole previewed image
//   pause | resume | step | reset
//   reload FILE                 load FILE as if the graph file had changed on disk
//   screenshot FILE             write the whole window (PNG) after this frame, + FILE.json
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fovea::editor {

struct ScriptCommand {
    uint32_t frame = 0;
    std::string verb;
    std::vector<std::string> args;
    std::string where;  // "file:line" for errors
};

// Throws InputError naming file:line: unknown command (did you mean), wrong argument count,
// frame not a number.
std::vector<ScriptCommand> parseInspectorScript(const std::filesystem::path& path);

}  // namespace fovea::editor
