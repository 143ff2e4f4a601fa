#include "core/vk/ShaderCompiler.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <glslang/build_info.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <deque>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <thread>

#include "core/util/Error.h"

namespace fovea::gpu {
namespace fs = std::filesystem;
namespace {

// Bump when the cache file layout or compile options change in a way the key does not capture.
constexpr const char* kCacheFormat = "fovea-spv-cache-1";
constexpr uint32_t kSpirvMagic = 0x07230203;

std::optional<std::string> readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

struct Fnv1a64 {
    uint64_t value = 0xcbf29ce484222325ull;
    void add(std::string_view bytes) {
        for (unsigned char c : bytes) {
            value ^= c;
            value *= 0x100000001b3ull;
        }
        // A separator keeps ("ab","c") and ("a","bc") apart.
        value ^= 0xff;
        value *= 0x100000001b3ull;
    }
};

std::string hex64(uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

// `#include "x"` (local) or `#include <x>`; returns the header name and whether it is local.
std::optional<std::pair<std::string, bool>> parseIncludeLine(std::string_view line) {
    size_t i = line.find_first_not_of(" \t");
    if (i == std::string_view::npos || line[i] != '#') return std::nullopt;
    i = line.find_first_not_of(" \t", i + 1);
    if (i == std::string_view::npos || line.substr(i, 7) != "include") return std::nullopt;
    i = line.find_first_not_of(" \t", i + 7);
    if (i == std::string_view::npos || (line[i] != '"' && line[i] != '<')) return std::nullopt;
    char close = line[i] == '"' ? '"' : '>';
    size_t end = line.find(close, i + 1);
    if (end == std::string_view::npos) return std::nullopt;
    return std::make_pair(std::string(line.substr(i + 1, end - i - 1)), close == '"');
}

// Local includes look next to the including file first, then in the shader root (so passes can
// write "common/x.glsl" from any depth); system includes only in the root.
std::optional<fs::path> findInclude(const std::string& header, const fs::path& includingFile,
                                    const fs::path& root, bool local) {
    std::vector<fs::path> candidates;
    if (local && !includingFile.empty()) candidates.push_back(includingFile.parent_path() / header);
    candidates.push_back(root / header);
    for (const auto& c : candidates) {
        std::error_code ec;
        if (fs::is_regular_file(c, ec)) return fs::weakly_canonical(c, ec);
    }
    return std::nullopt;
}

// Feeds the file and, recursively, every include it names into the hash. Includes inside
// disabled #if blocks are hashed too: conservative, and keeps the key computable without a
// preprocessor run. Missing includes are skipped here; glslang reports them if they matter.
void hashSources(const fs::path& file, const std::string& text, const fs::path& root,
                 std::set<fs::path>& visited, Fnv1a64& hash) {
    hash.add(file.string());
    hash.add(text);
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) {
        auto include = parseIncludeLine(line);
        if (!include) continue;
        auto found = findInclude(include->first, file, root, include->second);
        if (!found) {
            hash.add("missing:" + include->first);
            continue;
        }
        if (!visited.insert(*found).second) continue;
        if (auto content = readText(*found)) hashSources(*found, *content, root, visited, hash);
    }
}

bool plausibleSpirv(const std::vector<uint32_t>& words) {
    if (words.size() < 5 || words[0] != kSpirvMagic) return false;
    // Walk the instruction stream: a truncated or garbled file almost never lands exactly on the
    // end with every instruction length non-zero.
    size_t i = 5;
    while (i < words.size()) {
        uint32_t count = words[i] >> 16;
        if (count == 0) return false;
        i += count;
    }
    return i == words.size();
}

std::optional<std::vector<uint32_t>> readCache(const fs::path& file) {
    auto bytes = readText(file);
    if (!bytes || bytes->size() % 4 != 0) return std::nullopt;
    std::vector<uint32_t> words(bytes->size() / 4);
    std::copy(bytes->begin(), bytes->end(), reinterpret_cast<char*>(words.data()));
    if (!plausibleSpirv(words)) return std::nullopt;
    return words;
}

// Write-then-rename so concurrent processes never read a half-written file. Failures only cost
// a recompile next time, so they are ignored.
void writeCache(const fs::path& file, const std::vector<uint32_t>& words) {
    fs::path tmp = file;
    tmp += ".tmp" + std::to_string(::getpid()) + "-" +
           std::to_string(std::hash<std::thread::id>{}(std::this_thread::get_id()));
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) return;
        out.write(reinterpret_cast<const char*>(words.data()),
                  static_cast<std::streamsize>(words.size() * 4));
        if (!out) {
            out.close();
            std::error_code ec;
            fs::remove(tmp, ec);
            return;
        }
    }
    std::error_code ec;
    fs::rename(tmp, file, ec);
    if (ec) fs::remove(tmp, ec);
}

bool validIdentifier(const std::string& s) {
    if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
    return std::all_of(s.begin(), s.end(),
                       [](unsigned char c) { return std::isalnum(c) || c == '_'; });
}

std::optional<EShLanguage> stageFor(const fs::path& file) {
    const std::string ext = file.extension().string();
    if (ext == ".comp") return EShLangCompute;
    if (ext == ".vert") return EShLangVertex;
    if (ext == ".frag") return EShLangFragment;
    return std::nullopt;
}

// Resolves includes for glslang. It owns every result it hands out (glslang's interface is raw
// pointers), so releaseInclude has nothing to do and all memory goes with the includer.
class FileIncluder : public glslang::TShader::Includer {
public:
    FileIncluder(const ShaderCompiler& compiler, const fs::path& mainFile) : mCompiler(compiler) {
        mFiles[compiler.displayName(mainFile)] = mainFile;
    }
    IncludeResult* includeLocal(const char* header, const char* includer, size_t) override {
        return include(header, includer, true);
    }
    IncludeResult* includeSystem(const char* header, const char* includer, size_t) override {
        return include(header, includer, false);
    }
    void releaseInclude(IncludeResult*) override {}

private:
    IncludeResult* include(const char* header, const char* includer, bool local) {
        auto known = mFiles.find(includer ? includer : "");
        fs::path includingFile = known == mFiles.end() ? fs::path() : known->second;
        auto found = findInclude(header, includingFile, mCompiler.shaderRoot(), local);
        if (!found) {
            // Local lookups fall through to includeSystem, which produces the one error.
            if (local) return nullptr;
            std::string& why = mTexts.emplace_back("cannot find '" + std::string(header) +
                                                   "' (looked next to the including file "
                                                   "and in " +
                                                   mCompiler.shaderRoot().string() + ")");
            return mResults
                .emplace_back(std::make_unique<IncludeResult>("", why.data(), why.size(), nullptr))
                .get();
        }
        auto text = readText(*found);
        if (!text) return nullptr;
        std::string name = mCompiler.displayName(*found);
        mFiles[name] = *found;
        std::string& kept = mTexts.emplace_back(std::move(*text));
        return mResults
            .emplace_back(std::make_unique<IncludeResult>(name, kept.data(), kept.size(), nullptr))
            .get();
    }

    const ShaderCompiler& mCompiler;
    std::map<std::string, fs::path> mFiles;  // display name -> absolute path, for nested includes
    std::deque<std::string> mTexts;          // deque: references stay valid while growing
    std::vector<std::unique_ptr<IncludeResult>> mResults;
};

// glslang's log has lines like "ERROR: shaders/x.comp:12: 'foo' : undeclared identifier".
// Keeps only errors, as "shaders/x.comp:12: 'foo' : undeclared identifier"; errors without a
// location get the main file's name so every line says where to look.
std::string formatLog(const std::string& log, const std::string& mainName) {
    std::istringstream lines(log);
    std::string line;
    std::string out;
    while (std::getline(lines, line)) {
        if (line.rfind("ERROR: ", 0) != 0) continue;
        std::string body = line.substr(7);
        // Summary lines repeat what the real errors already said.
        if (body.find("No code generated") != std::string::npos ||
            body.find("compilation terminated") != std::string::npos)
            continue;
        while (!body.empty() && std::isspace(static_cast<unsigned char>(body.back())))
            body.pop_back();
        size_t colon = body.find(':');
        bool located = colon != std::string::npos && colon + 1 < body.size() &&
                       std::isdigit(static_cast<unsigned char>(body[colon + 1]));
        if (!located) body = mainName + ": " + body;
        out += (out.empty() ? "" : "\n") + body;
    }
    if (out.empty()) out = mainName + ": " + log;
    return out;
}

}  // namespace

ShaderCompiler::ShaderCompiler(fs::path shaderRoot, fs::path cacheDir)
    : mShaderRoot(fs::weakly_canonical(std::move(shaderRoot))) {
    glslang::InitializeProcess();  // reference counted by glslang, so one per compiler is fine
    if (!cacheDir.empty()) {
        std::error_code ec;
        fs::create_directories(cacheDir, ec);
        if (!ec && fs::is_directory(cacheDir, ec)) mCacheDir = std::move(cacheDir);
    }
}

ShaderCompiler::~ShaderCompiler() {
    glslang::FinalizeProcess();
}

size_t ShaderCompiler::cacheHits() const {
    std::lock_guard lock(mMutex);
    return mHits;
}

size_t ShaderCompiler::cacheMisses() const {
    std::lock_guard lock(mMutex);
    return mMisses;
}

std::string ShaderCompiler::displayName(const fs::path& absolutePath) const {
    fs::path rel = absolutePath.lexically_relative(mShaderRoot);
    if (rel.empty() || *rel.begin() == "..") return absolutePath.generic_string();
    return (mShaderRoot.filename() / rel).generic_string();
}

std::string ShaderCompiler::compilerVersion() {
    return std::string("glslang ") + std::to_string(GLSLANG_VERSION_MAJOR) + "." +
           std::to_string(GLSLANG_VERSION_MINOR) + "." + std::to_string(GLSLANG_VERSION_PATCH) +
           GLSLANG_VERSION_FLAVOR + " glsl460 vulkan1.3 spirv1.6 automap " + kCacheFormat;
}

fs::path ShaderCompiler::resolve(const std::string& path) const {
    fs::path p(path);
    return fs::weakly_canonical(p.is_absolute() ? p : mShaderRoot / p);
}

std::vector<uint32_t> ShaderCompiler::compile(const std::string& path,
                                              const ShaderDefines& defines) {
    fs::path file = resolve(path);
    std::string name = displayName(file);
    auto source = readText(file);
    if (!source || !fs::is_regular_file(file)) {
        throw RuntimeError(name + ": cannot open shader file (looked for " + file.string() + ")");
    }
    ShaderDefines sorted = defines;
    std::sort(sorted.begin(), sorted.end());
    for (const auto& [key, value] : sorted) {
        if (!validIdentifier(key) || value.find('\n') != std::string::npos)
            throw RuntimeError(name + ": invalid shader define '" + key + "=" + value + "'");
    }

    Fnv1a64 hash;
    hash.add(compilerVersion());
    for (const auto& [key, value] : sorted) hash.add(key + "=" + value);
    std::set<fs::path> visited{file};
    hashSources(file, *source, mShaderRoot, visited, hash);
    const uint64_t key = hash.value;

    {
        std::lock_guard lock(mMutex);
        if (auto it = mMemoryCache.find(key); it != mMemoryCache.end()) {
            ++mHits;
            return it->second;
        }
    }
    fs::path cacheFile = mCacheDir.empty() ? fs::path() : mCacheDir / (hex64(key) + ".spv");
    if (!cacheFile.empty()) {
        if (auto cached = readCache(cacheFile)) {
            std::lock_guard lock(mMutex);
            ++mHits;
            mMemoryCache[key] = *cached;
            return *cached;
        }
    }
    std::vector<uint32_t> spirv = compileUncached(file, *source, sorted);
    if (!cacheFile.empty()) writeCache(cacheFile, spirv);
    std::lock_guard lock(mMutex);
    ++mMisses;
    mMemoryCache[key] = spirv;
    return spirv;
}

std::vector<uint32_t> ShaderCompiler::compileUncached(const fs::path& file,
                                                      const std::string& source,
                                                      const ShaderDefines& sortedDefines) const {
    const std::string name = displayName(file);
    auto stage = stageFor(file);
    if (!stage)
        throw RuntimeError(name + ": unknown shader stage (expected .comp, .vert or .frag)");

    // The include extension is enabled here so shaders need not repeat it (same as shaderc).
    std::string preamble = "#extension GL_GOOGLE_include_directive : require\n";
    for (const auto& [key, value] : sortedDefines)
        preamble += "#define " + key + " " + value + "\n";

    glslang::TShader shader(*stage);
    const char* text = source.c_str();
    const int length = static_cast<int>(source.size());
    const char* sourceName = name.c_str();
    shader.setStringsWithLengthsAndNames(&text, &length, &sourceName, 1);
    shader.setPreamble(preamble.c_str());
    shader.setEntryPoint("main");
    shader.setEnvInput(glslang::EShSourceGlsl, *stage, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_6);
    // Resources without layout(binding = N) get the next free binding: passes bind by name, so
    // shader authors need not number them (same as glslangValidator --amb).
    shader.setAutoMapBindings(true);
    shader.setAutoMapLocations(true);
    const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
    FileIncluder includer(*this, file);
    if (!shader.parse(GetDefaultResources(), 460, ENoProfile, false, false, messages, includer)) {
        throw RuntimeError(formatLog(shader.getInfoLog(), name));
    }
    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages) || !program.mapIO())
        throw RuntimeError(formatLog(program.getInfoLog(), name));

    std::vector<uint32_t> spirv;
    spv::SpvBuildLogger logger;
    glslang::SpvOptions options;  // keeps OpName: reflection binds resources by name
    options.disableOptimizer = true;
    glslang::GlslangToSpv(*program.getIntermediate(*stage), spirv, &logger, &options);
    std::string spvErrors = logger.getAllMessages();
    if (spirv.empty()) throw RuntimeError(name + ": SPIR-V generation failed: " + spvErrors);
    return spirv;
}

}  // namespace fovea::gpu
