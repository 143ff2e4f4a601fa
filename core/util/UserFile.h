// Reading the files a user names (graph, camera path, bench file, glTF and its buffers, images):
// only regular files, after following links, and only up to a size limit per kind. A FIFO, a
// device such as /dev/zero or a directory is refused before it is opened: reading one could
// block forever or grow without bound (issue 33, class 1). The limits are in the README (exit
// status) and docs/scenes.md "Limits".
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace fovea {

// Graph files, camera paths and bench files: JSON text written by hand or by a script.
constexpr uint64_t kMaxJsonFileBytes = uint64_t(64) << 20;

// "" when the operating system can look `path` up, else why not: a component over 255 bytes, a
// path over 4095 bytes, or a loop of symbolic links. Checked where a path enters (CLI flags,
// bench files), so it is exit 2 naming the flag or pointer, not a raw "filesystem error" (exit 1)
// from deep inside a command (issue 33, class 5).
std::string pathProblem(const std::string& path);

// "" when `path` names an existing regular file (links followed), else why not: "file not
// found", "not a regular file (...)", or the file-system error.
std::string regularFileProblem(const std::filesystem::path& path);

// Reads a whole regular file of at most `maxBytes`. On failure returns false and a reason.
bool readRegularFile(const std::filesystem::path& path, uint64_t maxBytes,
                     std::vector<uint8_t>& out, std::string& error);

// readRegularFile as text; throws InputError(path, "", "cannot read <what>: <reason>").
std::string readUserTextFile(const std::filesystem::path& path, uint64_t maxBytes,
                             const std::string& what);

// Throws InputError(path, "", "cannot read <what>: <reason>") unless path is a regular file.
void requireRegularFile(const std::filesystem::path& path, const std::string& what);

// Writes `size` bytes to `path` (created or truncated), checking every step down to fclose, so
// that a full disk or a failed flush is a RuntimeError naming `path` ("cannot write: No space
// left on device"), never a silently short file.
void writeFileChecked(const std::filesystem::path& path, const void* data, size_t size);

}  // namespace fovea
