#include "eval/report/OutputFolder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "core/util/Error.h"

namespace fovea::eval {

namespace fs = std::filesystem;

namespace {

bool emptyButLock(const fs::path& dir) {
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.path().filename() != kOutputLockName) return false;
    return true;
}

}  // namespace

OutputFolder::OutputFolder(fs::path dir, const std::string& option, bool overwrite,
                           const std::string& report)
    : mDir(std::move(dir)) {
    std::error_code ec;
    fs::create_directories(mDir, ec);
    if (ec || !fs::is_directory(mDir))
        throw InputError(option, "",
                         "cannot create directory '" + mDir.string() + "': " + ec.message());
    const fs::path lock = mDir / kOutputLockName;
    mLockFd = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (mLockFd < 0)
        throw RuntimeError(lock.string() +
                           ": cannot create the lock file: " + std::strerror(errno));
    if (::flock(mLockFd, LOCK_EX | LOCK_NB) != 0) {
        ::close(mLockFd);
        mLockFd = -1;
        throw InputError(option, "",
                         "directory '" + mDir.string() +
                             "' is being written by another fovea run (its " + kOutputLockName +
                             " is locked)");
    }
    // Under the lock: the check that decides whether this run may write here.
    if (!overwrite && !emptyButLock(mDir)) {
        std::error_code ignored;
        fs::remove(lock, ignored);  // ours (held), not the user's
        ::close(mLockFd);
        mLockFd = -1;
        throw InputError(option, "",
                         "directory '" + mDir.string() +
                             "' is not empty; pass --overwrite to replace its files");
    }
    // A previous run's report would otherwise say "complete" about a half-written new run.
    fs::remove(mDir / report, ec);
    if (ec)
        throw RuntimeError((mDir / report).string() +
                           ": cannot remove the previous report: " + ec.message());
}

OutputFolder::~OutputFolder() {
    if (mLockFd < 0) return;
    std::error_code ignored;
    fs::remove(mDir / kOutputLockName, ignored);  // removed while still held: no window for a
    ::close(mLockFd);                             // second run to see our lock as free and stale
}

void OutputFolder::write(const std::string& name,
                         const std::function<void(const fs::path&)>& writeFile) const {
    const fs::path final = mDir / name;
    const fs::path partial = final.parent_path() / (".partial." + final.filename().string());
    std::error_code ec;
    try {
        writeFile(partial);
    } catch (const RuntimeError& e) {
        fs::remove(partial, ec);
        // The writer names the file it wrote (the partial one); the user knows the final name.
        std::string message = e.what();
        if (message.rfind(partial.string(), 0) == 0)
            message.replace(0, partial.string().size(), final.string());
        throw RuntimeError(message);
    } catch (...) {
        fs::remove(partial, ec);
        throw;
    }
    fs::rename(partial, final, ec);
    if (ec) {
        std::error_code ignored;
        fs::remove(partial, ignored);
        throw RuntimeError(final.string() + ": cannot write: " + ec.message());
    }
}

void OutputFolder::writeText(const std::string& name, const std::string& text) const {
    write(name, [&](const fs::path& path) {
        std::ofstream stream(path, std::ios::binary | std::ios::trunc);
        if (stream) stream.write(text.data(), std::streamsize(text.size()));
        if (stream) stream.flush();
        if (stream) stream.close();
        // A full disk usually shows at flush or close, not at write.
        if (!stream || stream.is_open())
            throw RuntimeError((mDir / name).string() +
                               ": cannot write: " + (errno ? std::strerror(errno) : "I/O error"));
    });
}

std::string safeFolderName(const std::string& name) {
    std::string out;
    for (char c : name) {
        const bool safe = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                          (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
        if (c == '.' && out.empty()) continue;  // no hidden, "." or ".." names
        out += safe ? c : '_';
        if (out.size() >= 100) break;
    }
    return out.empty() ? "run" : out;
}

}  // namespace fovea::eval
