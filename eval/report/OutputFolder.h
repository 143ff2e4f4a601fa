// The output folder of `fovea run`: taken by one process at a time, written so that an
// interrupted or failed run never leaves a folder that looks complete.
//
// - Taking it: the folder is created and `.fovea.lock` in it is locked (flock, released by the
//   kernel when the process dies, so a crash leaves no stale lock). The emptiness rule of
//   checkOutputDir is checked again under the lock: two runs started together on one --out
//   cannot both pass it. With --overwrite, a previous report (report.json of `run`, bench.json
//   of `bench`) is removed first, so the old report never sits beside new images.
// - Writing: every file goes to `.partial.<name>` (same folder, same extension, so a viewer
//   still knows the format) and is renamed when complete; every write is checked (a full disk is a
//   RuntimeError naming the file, exit 1). The report is written last, with "finished".
#pragma once
#include <filesystem>
#include <functional>
#include <string>

namespace fovea::eval {

class OutputFolder {
public:
    // `option` names the flag in errors (InputError: exit 2); `report` is the file that says the
    // folder is complete (removed first with `overwrite`).
    OutputFolder(std::filesystem::path dir, const std::string& option, bool overwrite,
                 const std::string& report = "report.json");
    ~OutputFolder();
    OutputFolder(const OutputFolder&) = delete;
    OutputFolder& operator=(const OutputFolder&) = delete;

    const std::filesystem::path& path() const { return mDir; }
    // Calls write(temporary path), then renames the temporary file to `name` (a relative path in
    // the folder: "reference/key.json" goes through "reference/.partial.key.json"). A throw from
    // `write` or a failed rename removes the temporary file and rethrows (RuntimeError).
    void write(const std::string& name,
               const std::function<void(const std::filesystem::path&)>& write) const;
    // Writes `text` (checked: open, write, flush, close) the same way.
    void writeText(const std::string& name, const std::string& text) const;

private:
    std::filesystem::path mDir;
    int mLockFd = -1;
};

// Name of the lock file inside a taken folder (ignored by the emptiness check).
inline constexpr const char* kOutputLockName = ".fovea.lock";

// A graph's free-text `name` as one safe folder name: characters other than letters, digits,
// '-', '_' and '.' become '_', leading dots are dropped ("../x" -> "_x", "/abs" -> "_abs"), and
// an empty result is "run". Never a path separator, "." or "..".
std::string safeFolderName(const std::string& name);

}  // namespace fovea::eval
