// Shared GoogleTest fixture for everything that touches the GPU. One validation-enabled context
// per test process (creating one per test would dominate runtime on lavapipe); every test fails
// if it produced any validation warning or error.
//
//   class MyPassTest : public GpuTest {};
//   TEST_F(MyPassTest, Works) { fovea::gpu::Image img(ctx(), {...}); ... }
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "core/vk/Context.h"

namespace fovea::test {

// The repository's shaders/ folder.
inline std::filesystem::path shaderRoot() {
    return FOVEA_SHADER_DIR;
}

// Created on first use (validation on), destroyed at process exit.
inline gpu::Context& sharedGpuContext() {
    static std::unique_ptr<gpu::Context> context;
    if (!context) {
        gpu::ContextOptions options;
        options.validation = true;
        context = std::make_unique<gpu::Context>(options);
        if (!context->validationEnabled())
            std::cerr
                << "GpuTest: WARNING: validation layer unavailable, GPU tests run without it\n";
    }
    return *context;
}

class GpuTest : public ::testing::Test {
protected:
    static gpu::Context& ctx() { return sharedGpuContext(); }

    void SetUp() override { ctx().clearValidationMessages(); }

    void TearDown() override {
        std::vector<std::string> messages = ctx().validationMessages();
        std::string text;
        for (const auto& m : messages) text += "\n  " + m;
        EXPECT_EQ(messages.size(), 0u) << "validation messages:" << text;
        ctx().clearValidationMessages();
    }
};

}  // namespace fovea::test

// TEST_F needs the fixture name unqualified.
using GpuTest = fovea::test::GpuTest;
