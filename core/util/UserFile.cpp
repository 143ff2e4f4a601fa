#include "core/util/UserFile.h"

#include <fstream>
#include <system_error>

#include "core/util/Error.h"

namespace fovea {

std::string regularFileProblem(const std::filesystem::path& path) {
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);  // follows symbolic links
    if (ec && ec != std::errc::no_such_file_or_directory) return ec.message();
    if (!std::filesystem::exists(status)) return "file not found";
    if (std::filesystem::is_directory(status)) return "is a directory, not a file";
    if (!std::filesystem::is_regular_file(status))
        return "not a regular file (a FIFO, socket or device could block or never end)";
    return "";
}

bool readRegularFile(const std::filesystem::path& path, uint64_t maxBytes,
                     std::vector<uint8_t>& out, std::string& error) {
    error = regularFileProblem(path);
    if (!error.empty()) return false;
    std::error_code ec;
    const uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) {
        error = "cannot read the file size: " + ec.message();
        return false;
    }
    if (size > maxBytes) {
        error = "file is " + std::to_string(size) + " bytes, more than the limit of " +
                std::to_string(maxBytes);
        return false;
    }
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = "cannot open the file (permission?)";
        return false;
    }
    out.resize(size_t(size));
    if (size > 0 && !in.read(reinterpret_cast<char*>(out.data()), std::streamsize(size))) {
        error = "read error";
        return false;
    }
    return true;
}

std::string readUserTextFile(const std::filesystem::path& path, uint64_t maxBytes,
                             const std::string& what) {
    std::vector<uint8_t> bytes;
    std::string error;
    if (!readRegularFile(path, maxBytes, bytes, error))
        throw InputError(path.string(), "", "cannot read " + what + ": " + error);
    return std::string(bytes.begin(), bytes.end());
}

void requireRegularFile(const std::filesystem::path& path, const std::string& what) {
    const std::string problem = regularFileProblem(path);
    if (!problem.empty())
        throw InputError(path.string(), "", "cannot read " + what + ": " + problem);
}

}  // namespace fovea
