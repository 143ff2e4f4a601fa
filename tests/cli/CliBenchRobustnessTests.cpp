// `fovea bench` writes its folder like `fovea run` (issue 16; eval/report/OutputFolder.h): every
// file is written checked under a temporary name and renamed, bench.json comes last with
// "finished", the folder is locked, and a non-empty --out is never written without --overwrite.
// Before, bench wrote through unchecked std::ofstream: a failed write exited 0 with missing or
// empty files. One 16x16 graph, 2 frames, a 2 spp rendered reference (lavapipe).
#include <fcntl.h>
#include <sys/file.h>

#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

Result smallBench(const TempDir& tmp, const fs::path& out, std::vector<std::string> extra = {}) {
    const json spec = {{"version", 1},
                       {"name", "tiny"},
                       {"scene", "builtin:cornell"},
                       {"size", {16, 16}},
                       {"frames", 2},
                       {"warmup", 1},
                       {"output", "acc.mean"},
                       {"reference", {{"render", {{"spp", 2}}}}},
                       {"graphs", {{{"label", "spp 1"}, {"file", kDemoGraph.string()}}}}};
    const fs::path file = tmp / "small.bench.json";
    writeText(file, spec.dump(2));
    std::vector<std::string> args = {"bench", file.string(), "--out", out.string(), "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    return cli(args);
}

bool anyPartialFile(const fs::path& dir) {
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.path().filename().string().rfind(".partial.", 0) == 0) return true;
    return false;
}

}  // namespace

TEST(CliBenchRobustness, FailedWriteExitsOneAndLeavesNoFinishedBench) {
    TempDir tmp;
    const fs::path out = tmp / "out";
    fs::create_directories(out);
    // A previous bench's result: with --overwrite it must not survive beside a failed run.
    writeText(out / "bench.json", R"({"finished": true})");
    // A directory where bench.md's temporary file goes: the write fails like a full disk would
    // (the tests run as root, so a read-only folder would not fail).
    fs::create_directories(out / ".partial.bench.md");
    Result r = smallBench(tmp, out, {"--overwrite"});
    EXPECT_EQ(r.code, 1) << r.describe();
    EXPECT_TRUE(contains(r.err, "bench.md")) << r.describe();
    EXPECT_FALSE(fs::exists(out / "bench.json")) << "a bench.json beside a failed bench";
    EXPECT_FALSE(fs::exists(out / "bench.md"));
    EXPECT_FALSE(fs::exists(out / ".fovea.lock"));
    fs::remove_all(out / ".partial.bench.md");

    // The same folder, now writable: complete, "finished", no temporary files; the reference
    // rendered by the failed run is reused (its key.json was written last, checked).
    Result ok = smallBench(tmp, out, {"--overwrite"});
    ASSERT_EQ(ok.code, 0) << ok.describe();
    const json bench = json::parse(readText(out / "bench.json"));
    EXPECT_EQ(bench.at("finished"), true);
    EXPECT_EQ(bench.at("reference").at("cached"), true);
    for (const char* f : {"bench.csv", "bench.md", "bench.svg"})
        EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
    EXPECT_FALSE(anyPartialFile(out));
    EXPECT_FALSE(fs::exists(out / ".fovea.lock"));
}

TEST(CliBenchRobustness, NonEmptyOrLockedOutIsNotWritten) {
    TempDir tmp;
    const fs::path out = tmp / "out";
    fs::create_directories(out);
    writeText(out / "mine.txt", "the user's file");
    expectInputError(smallBench(tmp, out), {"--out", "not empty", "--overwrite"});
    EXPECT_EQ(readText(out / "mine.txt"), "the user's file");
    EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 1)
        << "bench wrote into a folder it refused";

    // A folder locked by a live run or bench is refused even with --overwrite (before any
    // rendering: no device work).
    const int fd = ::open((out / ".fovea.lock").c_str(), O_RDWR | O_CREAT, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
    expectInputError(smallBench(tmp, out, {"--overwrite"}), {"--out", "another fovea run"});
    ::close(fd);
    EXPECT_FALSE(fs::exists(out / "bench.json"));
}
