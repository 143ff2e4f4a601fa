// Tests of shader compilation (glslang + cache) and reflection (spirv-cross).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

#include "core/util/Error.h"
#include "core/vk/ComputePipeline.h"
#include "core/vk/ShaderCompiler.h"
#include "core/vk/ShaderReflection.h"
#include "tests/graph/GpuTestFixture.h"

using namespace fovea;
using namespace fovea::gpu;
namespace fs = std::filesystem;

namespace {

class ShaderTest : public GpuTest {};

// A scratch folder removed at the end of the test.
class TempDir {
public:
    TempDir() {
        std::random_device rd;
        mPath = fs::temp_directory_path() / ("fovea_shader_test_" + std::to_string(rd()));
        fs::create_directories(mPath);
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(mPath, ec);
    }
    const fs::path& path() const { return mPath; }
    void write(const std::string& relative, const std::string& text) const {
        fs::create_directories((mPath / relative).parent_path());
        std::ofstream(mPath / relative, std::ios::binary | std::ios::trunc) << text;
    }

private:
    fs::path mPath;
};

std::string compileError(ShaderCompiler& compiler, const std::string& path,
                         const ShaderDefines& defines = {}) {
    try {
        compiler.compile(path, defines);
    } catch (const RuntimeError& e) {
        return e.what();
    }
    return "";
}

const char* kMinimal = R"(#version 460
layout(local_size_x = 1) in;
layout(set = 0, binding = 0, r32f) uniform writeonly image2D img;
void main() { imageStore(img, ivec2(0), vec4(VALUE)); }
)";

}  // namespace

// Every compute shader in the repository, found at run time so new passes are covered: it must
// compile without defines, reflect, and make a valid pipeline (validation checks the latter).
TEST_F(ShaderTest, EveryShaderCompilesAndReflects) {
    std::vector<fs::path> shaders;
    for (const auto& entry : fs::recursive_directory_iterator(fovea::test::shaderRoot()))
        if (entry.is_regular_file() && entry.path().extension() == ".comp")
            shaders.push_back(entry.path());
    std::sort(shaders.begin(), shaders.end());
    ASSERT_GE(shaders.size(), 4u);
    for (const auto& file : shaders) {
        std::string relative = fs::relative(file, fovea::test::shaderRoot()).generic_string();
        SCOPED_TRACE(relative);
        try {
            std::vector<uint32_t> spirv = ctx().shaderCompiler().compile(relative);
            ShaderInterface reflected = reflectShader(spirv);
            EXPECT_GE(reflected.localSize[0], 1u);
            ComputePipeline pipeline(ctx(), relative);
        } catch (const std::exception& e) {
            ADD_FAILURE() << e.what();
        }
    }
}

TEST(ShaderCompiler, IncludesResolveRelativeThenRoot) {
    TempDir dir;
    fs::path root = dir.path() / "shaders";
    dir.write("shaders/common/a.glsl",
              "#include \"b.glsl\"\nfloat fromA() { return fromB() + 1.0; }\n");
    dir.write("shaders/common/b.glsl", "float fromB() { return 2.0; }\n");
    dir.write("shaders/pass/local.glsl", "float fromLocal() { return 4.0; }\n");
    // "common/a.glsl" is not next to x.comp, so it comes from the root; a.glsl's "b.glsl"
    // resolves next to a.glsl; "local.glsl" next to x.comp.
    dir.write("shaders/pass/x.comp", R"(#version 460
#include "common/a.glsl"
#include "local.glsl"
layout(local_size_x = 4, local_size_y = 2, local_size_z = 3) in;
layout(set = 0, binding = 0, r32f) uniform writeonly image2D img;
void main() { imageStore(img, ivec2(0), vec4(fromA() + fromLocal())); }
)");
    ShaderCompiler compiler(root);
    auto spirv = compiler.compile("pass/x.comp");
    ShaderInterface reflected = reflectShader(spirv);
    EXPECT_EQ(reflected.localSize, (std::array<uint32_t, 3>{4, 2, 3}));
    ASSERT_EQ(reflected.bindings.size(), 1u);
    EXPECT_EQ(reflected.bindings[0].name, "img");
    EXPECT_EQ(reflected.bindings[0].imageFormat, vk::Format::eR32Sfloat);
    EXPECT_TRUE(reflected.bindings[0].writeonly);

    dir.write("shaders/pass/sys.comp", R"(#version 460
#include <common/b.glsl>
layout(local_size_x = 1) in;
layout(set = 0, binding = 0, r32f) uniform writeonly image2D img;
void main() { imageStore(img, ivec2(0), vec4(fromB())); }
)");
    EXPECT_NO_THROW(compiler.compile("pass/sys.comp"));
}

TEST(ShaderCompiler, ErrorsNameFileAndLine) {
    TempDir dir;
    fs::path root = dir.path() / "shaders";
    dir.write("shaders/bad.comp",
              "#version 460\nlayout(local_size_x = 1) in;\nvoid main() {\n    float x = "
              "undefinedThing;\n}\n");
    dir.write("shaders/common/broken.glsl",
              "float ok() { return 1.0; }\nfloat broken() { return nope; }\n");
    dir.write("shaders/uses_broken.comp",
              "#version 460\n#include \"common/broken.glsl\"\nlayout(local_size_x = 1) in;\nvoid "
              "main() {}\n");
    dir.write("shaders/missing_include.comp",
              "#version 460\n\n#include \"common/nothere.glsl\"\nlayout(local_size_x = 1) "
              "in;\nvoid main() {}\n");
    ShaderCompiler compiler(root);

    std::string e = compileError(compiler, "bad.comp");
    EXPECT_EQ(e.rfind("shaders/bad.comp:4:", 0), 0u) << e;
    EXPECT_NE(e.find("undefinedThing"), std::string::npos) << e;

    e = compileError(compiler, "uses_broken.comp");
    EXPECT_NE(e.find("shaders/common/broken.glsl:2:"), std::string::npos) << e;

    e = compileError(compiler, "missing_include.comp");
    EXPECT_NE(e.find("shaders/missing_include.comp:3:"), std::string::npos) << e;
    EXPECT_NE(e.find("nothere.glsl"), std::string::npos) << e;

    e = compileError(compiler, "no/such/file.comp");
    EXPECT_EQ(e.rfind("shaders/no/such/file.comp:", 0), 0u) << e;

    // The repository's compiler names files "shaders/...".
    ShaderCompiler repo(fovea::test::shaderRoot());
    e = compileError(repo, "test/does_not_exist.comp");
    EXPECT_EQ(e.rfind("shaders/test/does_not_exist.comp:", 0), 0u) << e;
}

TEST(ShaderCompiler, DefinesChangeSpirv) {
    ShaderCompiler compiler(fovea::test::shaderRoot());
    auto plain = compiler.compile("test/fill.comp");
    auto coords = compiler.compile("test/fill.comp", {{"ADD_COORDS", "1"}});
    EXPECT_NE(plain, coords);
    // Order-insensitive, and the in-memory cache returns the same words.
    auto a = compiler.compile("test/fill.comp", {{"ADD_COORDS", "1"}, {"UNUSED", ""}});
    auto b = compiler.compile("test/fill.comp", {{"UNUSED", ""}, {"ADD_COORDS", "1"}});
    EXPECT_EQ(a, b);
    EXPECT_NE(compileError(compiler, "test/fill.comp", {{"BAD NAME", "1"}}), "");
}

TEST(ShaderCompiler, DiskCacheHitsMissesAndCorruption) {
    TempDir dir;
    fs::path root = dir.path() / "shaders";
    fs::path cache = dir.path() / "cache";
    dir.write("shaders/common/value.glsl", "#define VALUE 1.0\n");
    dir.write("shaders/m.comp", std::string("#version 460\n#include \"common/value.glsl\"\n") +
                                    (kMinimal + std::string(kMinimal).find('\n') + 1));
    std::vector<uint32_t> first;
    {
        ShaderCompiler compiler(root, cache);
        first = compiler.compile("m.comp");
        EXPECT_EQ(compiler.cacheMisses(), 1u);
        EXPECT_EQ(compiler.cacheHits(), 0u);
        EXPECT_EQ(compiler.compile("m.comp"), first);
        EXPECT_EQ(compiler.cacheHits(), 1u);
        compiler.compile("m.comp", {{"EXTRA", "2"}});  // different define: a miss
        EXPECT_EQ(compiler.cacheMisses(), 2u);
    }
    size_t files = 0;
    for (const auto& f : fs::directory_iterator(cache)) files += f.path().extension() == ".spv";
    EXPECT_EQ(files, 2u);
    {
        // A new compiler (new process, in effect) hits the disk cache.
        ShaderCompiler compiler(root, cache);
        EXPECT_EQ(compiler.compile("m.comp"), first);
        EXPECT_EQ(compiler.cacheHits(), 1u);
        EXPECT_EQ(compiler.cacheMisses(), 0u);
    }
    // Editing an include changes the key.
    dir.write("shaders/common/value.glsl", "#define VALUE 2.0\n");
    {
        ShaderCompiler compiler(root, cache);
        EXPECT_NE(compiler.compile("m.comp"), first);
        EXPECT_EQ(compiler.cacheMisses(), 1u);
    }
    // Corrupt every cache file: they are ignored, recompiled and rewritten.
    for (const auto& f : fs::directory_iterator(cache))
        std::ofstream(f.path(), std::ios::binary | std::ios::trunc) << "garbage!";
    dir.write("shaders/common/value.glsl", "#define VALUE 1.0\n");
    {
        ShaderCompiler compiler(root, cache);
        EXPECT_EQ(compiler.compile("m.comp"), first);
        EXPECT_EQ(compiler.cacheMisses(), 1u);
    }
    {
        ShaderCompiler compiler(root, cache);
        EXPECT_EQ(compiler.compile("m.comp"), first);
        EXPECT_EQ(compiler.cacheHits(), 1u);
    }
}

TEST(ShaderCompiler, UnwritableCacheDirFallsBackToMemory) {
    TempDir dir;
    dir.write("blocker", "a file where the cache folder should be");
    ShaderCompiler compiler(fovea::test::shaderRoot(), dir.path() / "blocker" / "cache");
    EXPECT_TRUE(compiler.cacheDir().empty());
    EXPECT_NO_THROW(compiler.compile("test/fill.comp"));
}

TEST(ShaderReflection, BindingsAndPushConstants) {
    ShaderCompiler compiler(fovea::test::shaderRoot());
    ShaderInterface copy = reflectShader(compiler.compile("test/copy.comp"));
    ASSERT_EQ(copy.bindings.size(), 2u);
    EXPECT_EQ(copy.bindings[0].name, "src");
    EXPECT_EQ(copy.bindings[0].kind, DescriptorKind::SampledImage);
    EXPECT_EQ(copy.bindings[1].name, "dst");
    EXPECT_EQ(copy.bindings[1].binding, 1u);
    EXPECT_EQ(copy.bindings[1].kind, DescriptorKind::StorageImage);
    EXPECT_EQ(copy.bindings[1].imageFormat, vk::Format::eR32G32B32A32Sfloat);
    EXPECT_EQ(copy.localSize, (std::array<uint32_t, 3>{16, 4, 1}));
    EXPECT_EQ(copy.pushConstantSize, 0u);

    ShaderInterface scale = reflectShader(compiler.compile("test/scale_buffer.comp"));
    ASSERT_NE(scale.findBinding("inputData"), nullptr);  // instance name wins
    EXPECT_EQ(scale.findBinding("Input"), nullptr);
    ASSERT_NE(scale.findBinding("Output"), nullptr);  // no instance name: block name
    EXPECT_TRUE(scale.findBinding("inputData")->readonly);
    EXPECT_TRUE(scale.findBinding("Output")->writeonly);
    EXPECT_EQ(scale.findBinding("Output")->kind, DescriptorKind::StorageBuffer);
    ASSERT_EQ(scale.pushConstants.size(), 3u);
    EXPECT_EQ(scale.pushConstantSize, 16u);
    const auto* s = scale.findPushConstant("scale");
    const auto* c = scale.findPushConstant("count");
    ASSERT_TRUE(s && c);
    EXPECT_EQ(s->typeName, "float");
    EXPECT_EQ(s->offset, 0u);
    EXPECT_EQ(s->size, 4u);
    EXPECT_EQ(c->typeName, "uint");
    EXPECT_EQ(c->offset, 4u);

    ShaderInterface rw = reflectShader(compiler.compile("test/read_write.comp"));
    ASSERT_NE(rw.findBinding("params"), nullptr);
    EXPECT_EQ(rw.findBinding("params")->kind, DescriptorKind::UniformBuffer);
    EXPECT_FALSE(rw.findBinding("target")->readonly);
    EXPECT_FALSE(rw.findBinding("target")->writeonly);
    EXPECT_EQ(rw.findBinding("target")->imageFormat, vk::Format::eR16G16B16A16Sfloat);
}

TEST(ShaderReflection, PushConstantTypeNames) {
    TempDir dir;
    dir.write("shaders/types.comp", R"(#version 460
layout(local_size_x = 1) in;
layout(push_constant) uniform Push {
    mat4 m;
    ivec2 i2;
    uvec2 u2;
    vec3 v3;
    int i;
    vec4 arr[2];
} pc;
layout(set = 0, binding = 0, r32ui) uniform uimage2D img;
void main() { imageStore(img, ivec2(0), uvec4(pc.m[0][0] + pc.v3.x + pc.arr[1].x + float(pc.i + pc.i2.x) + float(pc.u2.y))); }
)");
    ShaderCompiler compiler(dir.path() / "shaders");
    ShaderInterface r = reflectShader(compiler.compile("types.comp"));
    std::vector<std::pair<std::string, std::string>> got;
    for (const auto& m : r.pushConstants) got.emplace_back(m.name, m.typeName);
    std::vector<std::pair<std::string, std::string>> want{{"m", "mat4"},   {"i2", "ivec2"},
                                                          {"u2", "uvec2"}, {"v3", "vec3"},
                                                          {"i", "int"},    {"arr", "vec4[2]"}};
    EXPECT_EQ(got, want);
    EXPECT_EQ(r.findPushConstant("m")->size, 64u);
    EXPECT_EQ(r.findPushConstant("i")->offset, 92u);  // packed after the 12-byte vec3
    EXPECT_EQ(r.findPushConstant("arr")->size, 32u);
    EXPECT_EQ(r.pushConstantSize, 128u);
    EXPECT_EQ(r.bindings[0].imageFormat, vk::Format::eR32Uint);
}
