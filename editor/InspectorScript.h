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
//   compare PASS.FIELD|reference|off   a second image beside the preview
//   difference on|off           right pane: |A - B| instead of B
//   zoom FACTOR U V             zoom (1 = fit .. 64) centred on (U, V) in [0,1]^2 of the image
//   camera path|freefly         follow the camera path, or steer (free-fly from the current pose)
//   move RIGHT UP FORWARD       free-fly: move in camera space (scene units); turns free-fly on
//   look YAW PITCH              free-fly: turn (degrees); turns free-fly on
//   place PASS X Y              put a node at (X, Y) in the graph view (like dragging it)
//   saveas FILE                 write the graph + node positions (existing file: --overwrite)
//   previewshot FILE            the preview at its own size: .exr full float, else PNG as shown
//   rebuild                     rebuild the whole graph (to compare with a parameter update)
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
