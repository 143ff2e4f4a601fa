// GLSL -> SPIR-V through glslang, with #include resolution and a content-addressed disk cache.
#pragma once
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace fovea::gpu {

// Preprocessor defines ("NAME", "VALUE"); an empty value defines NAME without a value. Order does
// not matter: the cache key sorts them.
using ShaderDefines = std::vector<std::pair<std::string, std::string>>;

class ShaderCompiler {
public:
    // cacheDir empty (or not creatable) = no disk cache; the in-memory cache is always on.
    explicit ShaderCompiler(std::filesystem::path shaderRoot = FOVEA_SHADER_DIR,
                            std::filesystem::path cacheDir = {});
    ~ShaderCompiler();
    ShaderCompiler(const ShaderCompiler&) = delete;
    ShaderCompiler& operator=(const ShaderCompiler&) = delete;

    // `path` is relative to the shader root ("tonemap/tonemap.comp") or absolute; the stage comes
    // from the extension (.comp, .vert, .frag). `#include "x"` resolves relative to the including
    // file, then the shader root; `#include <x>` only from the root. GLSL 460 -> SPIR-V 1.6 for
    // Vulkan 1.3; GL_GOOGLE_include_directive is pre-enabled; resources without an explicit
    // layout(binding = N) are numbered automatically (set 0). Throws RuntimeError whose message
    // holds one "shaders/x/y.comp:LINE: error" line per glslang error (also for a missing file or
    // include). Thread-safe.
    std::vector<uint32_t> compile(const std::string& path, const ShaderDefines& defines = {});

    // Hits count in-memory and disk cache hits; misses count real compilations.
    size_t cacheHits() const;
    size_t cacheMisses() const;

    const std::filesystem::path& shaderRoot() const { return mShaderRoot; }
    // Empty when the disk cache is off.
    const std::filesystem::path& cacheDir() const { return mCacheDir; }
    // The path as errors show it: "<root folder name>/<relative path>", e.g. "shaders/x/y.comp".
    std::string displayName(const std::filesystem::path& absolutePath) const;
    // Part of every cache key, so a glslang upgrade or option change never reuses stale SPIR-V.
    static std::string compilerVersion();

private:
    std::vector<uint32_t> compileUncached(const std::filesystem::path& file,
                                          const std::string& source,
                                          const ShaderDefines& sortedDefines) const;
    std::filesystem::path resolve(const std::string& path) const;

    std::filesystem::path mShaderRoot;
    std::filesystem::path mCacheDir;
    mutable std::mutex mMutex;  // guards the statistics and the memory cache
    std::unordered_map<uint64_t, std::vector<uint32_t>> mMemoryCache;
    size_t mHits = 0;
    size_t mMisses = 0;
};

}  // namespace fovea::gpu
