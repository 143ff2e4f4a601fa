// The message of the InputError a piece of code throws, for tests of bad input.
#pragma once
#include <gtest/gtest.h>

#include <exception>
#include <string>

#include "core/util/Error.h"

namespace fovea::test {

// The InputError message of `f`, failing the test when nothing (or something else) is thrown.
template <typename F>
std::string inputErrorOf(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    } catch (const std::exception& e) {
        ADD_FAILURE() << "not an InputError: " << e.what();
        return {};
    }
    ADD_FAILURE() << "no error";
    return {};
}

}  // namespace fovea::test
