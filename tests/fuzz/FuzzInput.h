// Shared by the fuzz targets (docs/testing.md "Fuzzing"). Each target is one
// LLVMFuzzerTestOneInput over one reader a user feeds; built with libFuzzer under clang
// (FOVEA_FUZZ=ON) or, in any tree, with FuzzReplayMain.cpp, which replays saved inputs.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>

#include "core/util/Error.h"

namespace fovea::fuzz {

// The readers under test take paths (they check the file kind and size the way a user's file is
// checked), so the input is written to a file in this process's own folder under the system
// temp directory (created once, removed at exit). `name` may hold folders. Returns its path.
std::filesystem::path writeInput(const uint8_t* data, size_t size, const std::string& name);
// That folder.
const std::filesystem::path& inputFolder();

// Bad input must end in fovea::InputError (exit 2 with file and pointer). Any other exception
// would reach the user as exit 1 "runtime failure" with a library's message: a finding, so the
// target aborts and libFuzzer keeps the input (as it does for a crash, leak, hang or OOM).
template <class Body>
void expectOnlyInputErrors(const char* target, Body&& body) {
    try {
        body();
    } catch (const InputError&) {
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fuzz %s: not an InputError: %s\n", target, e.what());
        std::abort();
    }
}

}  // namespace fovea::fuzz
