#include "core/util/UserFile.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <system_error>

#include "core/util/Error.h"

namespace fovea {

std::string pathProblem(const std::string& path) {
    constexpr size_t kMaxPath = 4095, kMaxComponent = 255;  // Linux PATH_MAX - 1, NAME_MAX
    if (path.size() > kMaxPath)
        return "the path is " + std::to_string(path.size()) + " bytes, more than the " +
               std::to_string(kMaxPath) + " a path may have";
    size_t start = 0;
    while (start <= path.size()) {
        size_t end = path.find('/', start);
        if (end == std::string::npos) end = path.size();
        if (end - start > kMaxComponent)
            return "a name in the path is " + std::to_string(end - start) + " bytes ('" +
                   path.substr(start, 24) + "...'), more than the " +
                   std::to_string(kMaxComponent) + " a file name may have";
        start = end + 1;
    }
    std::error_code ec;
    (void)std::filesystem::status(path, ec);  // only the error matters here
    if (ec == std::errc::too_many_symbolic_link_levels) return "a loop of symbolic links";
    return "";
}

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

void writeFileChecked(const std::filesystem::path& path, const void* data, size_t size) {
    auto fail = [&](int error) {
        throw RuntimeError(path.string() +
                           ": cannot write: " + (error ? std::strerror(error) : "unknown error"));
    };
    errno = 0;
    std::FILE* raw = std::fopen(path.c_str(), "wb");
    if (!raw) fail(errno);
    auto closer = [](std::FILE* f) { std::fclose(f); };
    std::unique_ptr<std::FILE, decltype(closer)> file(raw, closer);
    if (size > 0 && std::fwrite(data, 1, size, file.get()) != size) fail(errno);
    if (std::fflush(file.get()) != 0) fail(errno);
    errno = 0;
    if (std::fclose(file.release()) != 0) fail(errno);  // the last buffered bytes reach the disk
}

}  // namespace fovea
