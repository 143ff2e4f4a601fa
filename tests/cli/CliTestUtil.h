// Helpers of the `fovea` executable tests (CliTests.cpp, CliSceneTests.cpp): spawn FOVEA_EXE
// with captured output in a per-test temporary directory, and small file/JSON helpers.
#pragma once
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/image/ImageIO.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace fovea::clitest {

const fs::path kRepo = fs::path(FOVEA_TEST_DIR).parent_path();
const fs::path kDemo = kRepo / "graphs" / "tests" / "utility_demo.json";
const fs::path kDemoGraph =
    kRepo / "graphs" / "demo.json";  // outputs pt.radiance, acc.mean, tm.ldr
const fs::path kPathTraceGraph = kRepo / "graphs" / "pathtrace.json";

inline std::string readText(const fs::path& path) {
    std::ifstream stream(path, std::ios::binary);
    std::stringstream buffer;
    buffer << stream.rdbuf();
    return buffer.str();
}

inline json readReport(const fs::path& out) {
    return json::parse(readText(out / "report.json"));
}

// The entry of pass `name` in a report.json's `passes` (throws when there is none).
inline const json& passNamed(const json& report, const std::string& name) {
    for (const auto& p : report.at("passes"))
        if (p.at("name") == name) return p;
    throw std::runtime_error("no pass " + name + " in report.json");
}

inline void writeText(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
}

// A fresh, uniquely named directory under the system temp dir; removed with everything in it.
class TempDir {
public:
    TempDir() {
        static std::atomic<int> counter{0};
        const auto* info = testing::UnitTest::GetInstance()->current_test_info();
        std::string test = info ? info->name() : "suite";
        std::random_device random;
        mPath = fs::temp_directory_path() /
                ("fovea_cli_" + test + "_" + std::to_string(::getpid()) + "_" +
                 std::to_string(counter++) + "_" + std::to_string(random() % 1000000));
        fs::remove_all(mPath);
        fs::create_directories(mPath);
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(mPath, ignored);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const fs::path& path() const { return mPath; }
    fs::path operator/(const std::string& name) const { return mPath / name; }

private:
    fs::path mPath;
};

inline std::string shellQuote(const std::string& s) {
    std::string out = "'";
    for (char c : s) {
        if (c == '\'')
            out += "'\\''";
        else
            out += c;
    }
    return out + "'";
}

struct Result {
    int code = -1;
    std::string out, err;
    std::string command;
    // For assertion messages.
    std::string describe() const {
        return "command: " + command + "\nexit code: " + std::to_string(code) + "\nstdout:\n" +
               out + "\nstderr:\n" + err;
    }
};

// Runs FOVEA_EXE with `args` (no shell interpretation of the arguments), capturing both streams.
inline Result cli(const std::vector<std::string>& args) {
    TempDir capture;
    Result r;
    r.command = shellQuote(FOVEA_EXE);
    for (const auto& a : args) r.command += " " + shellQuote(a);
    std::string line = r.command + " </dev/null >" + shellQuote((capture / "stdout").string()) +
                       " 2>" + shellQuote((capture / "stderr").string());
    int status = std::system(line.c_str());
    if (status != -1 && WIFEXITED(status))
        r.code = WEXITSTATUS(status);
    else
        r.code = 1000 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);  // never 0, 1 or 2
    // (a child killed by a signal shows up as exit code 128 + signal through the shell)
    r.out = readText(capture / "stdout");
    r.err = readText(capture / "stderr");
    return r;
}

inline bool contains(const std::string& text, const std::string& fragment) {
    return text.find(fragment) != std::string::npos;
}

// Exit status 2 and stderr containing every fragment.
inline void expectInputError(const Result& r, std::initializer_list<std::string> fragments) {
    EXPECT_EQ(r.code, 2) << r.describe();
    for (const auto& f : fragments)
        EXPECT_TRUE(contains(r.err, f)) << "'" << f << "' not in stderr\n" << r.describe();
}

// `fovea run graph --out DIR --frames 2 --size 32x32 extra...`; output in a fresh subdirectory.
inline Result runSmall(const fs::path& graph, const fs::path& out,
                       std::vector<std::string> extra = {}) {
    std::vector<std::string> args = {"run", graph.string(), "--out", out.string(), "--frames",
                                     "2",   "--size",       "32x32"};
    args.insert(args.end(), extra.begin(), extra.end());
    return cli(args);
}

inline std::vector<float> pixels(const fs::path& exr) {
    return ::fovea::image::readImage(exr).pixels;
}

inline void expectStats(const json& stats, const std::string& what) {
    ASSERT_TRUE(stats.is_object()) << what;
    for (const char* key : {"mean", "median", "min", "max"}) {
        ASSERT_TRUE(stats.contains(key) && stats[key].is_number()) << what << "." << key;
        double v = stats[key].get<double>();
        EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << what << "." << key << " = " << v;
    }
    double mn = stats["min"], mx = stats["max"], mean = stats["mean"], med = stats["median"];
    EXPECT_LE(mn, mean) << what;
    EXPECT_LE(mean, mx) << what;
    EXPECT_LE(mn, med) << what;
    EXPECT_LE(med, mx) << what;
}

}  // namespace fovea::clitest
