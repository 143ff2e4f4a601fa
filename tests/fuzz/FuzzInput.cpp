#include "tests/fuzz/FuzzInput.h"

#include <unistd.h>

#include "core/util/UserFile.h"

namespace fovea::fuzz {
namespace {

struct InputFolder {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("fovea-fuzz-" + std::to_string(::getpid()));
    InputFolder() { std::filesystem::create_directories(path); }
    ~InputFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path, ignored);
    }
};

}  // namespace

const std::filesystem::path& inputFolder() {
    static InputFolder folder;
    return folder.path;
}

std::filesystem::path writeInput(const uint8_t* data, size_t size, const std::string& name) {
    const std::filesystem::path file = inputFolder() / name;
    std::filesystem::create_directories(file.parent_path());
    writeFileChecked(file, data, size);
    return file;
}

}  // namespace fovea::fuzz
