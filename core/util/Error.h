// Error classes shared by every room of fovea. The CLI maps them to exit codes:
// InputError -> 2 (bad graph / glTF / parameter / CLI argument), RuntimeError -> 1.
#pragma once
#include <stdexcept>
#include <string>

namespace fovea {

// Bad user input. The message always names the file (or CLI flag) and, for JSON, the pointer:
// "graphs/x.json: /edges/3/to: pass 'pt' has no input 'colour' (did you mean 'color'?)".
class InputError : public std::runtime_error {
public:
    explicit InputError(const std::string& message) : std::runtime_error(message) {}
    InputError(const std::string& file, const std::string& pointer, const std::string& message)
        : std::runtime_error(file + ": " + (pointer.empty() ? std::string() : pointer + ": ") +
                             message),
          mFile(file),
          mPointer(pointer) {}
    const std::string& file() const { return mFile; }
    const std::string& pointer() const { return mPointer; }

private:
    std::string mFile;
    std::string mPointer;
};

// Failure while running valid input: no device, out of memory, shader compile failure, I/O.
class RuntimeError : public std::runtime_error {
public:
    explicit RuntimeError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace fovea
