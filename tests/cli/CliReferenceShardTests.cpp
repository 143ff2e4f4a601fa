// Sharded references (docs/cluster.md, eval/reference/ReferenceShards.h): `fovea reference
// --shard I/N` (by samples) and `--path-frames A:B --frames-of I/N` (by frames), and `fovea
// merge`. A merged sample-sharded reference equals the single run within float rounding (the
// single run's Accumulate keeps a float running mean; merge sums in double); a merged
// frame-sharded one equals it exactly. Merge refuses shards that do not belong together.
// Tiny sizes (lavapipe): 48x32, 8 spp.
#include "tests/cli/CliTestUtil.h"

using namespace fovea::clitest;

namespace {

const std::string kSize = "48x32";

Result reference(const std::vector<std::string>& extra, const fs::path& out) {
    std::vector<std::string> args = {"reference", "--spp", "8",          "--size",
                                     kSize,       "--out", out.string(), "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    return cli(args);
}

double maxAbsDifference(const fovea::image::ImageRGBA& a, const fovea::image::ImageRGBA& b) {
    EXPECT_EQ(a.pixels.size(), b.pixels.size());
    double d = 0;
    for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i)
        d = std::max(d, double(std::abs(a.pixels[i] - b.pixels[i])));
    return d;
}

}  // namespace

TEST(CliReferenceShard, SampleShardsMergeToTheSingleRun) {
    TempDir tmp;
    ASSERT_EQ(reference({}, tmp / "single").code, 0);
    std::vector<std::string> merge = {"merge"};
    json covered = json::array();
    for (int i : {2, 0, 3, 1}) {  // any order
        const fs::path dir = tmp / ("shard" + std::to_string(i));
        Result r = reference({"--shard", std::to_string(i) + "/4"}, dir);
        ASSERT_EQ(r.code, 0) << r.describe();
        const json info = json::parse(readText(dir / "shard.json"));
        EXPECT_EQ(info.at("frames"), json::array({2 * i, 2 * i + 2})) << "8 frames in 4 blocks";
        EXPECT_EQ(info.at("samples"), 2);
        merge.push_back(dir.string());
    }
    const auto sum0 = fovea::image::readImage(tmp / "shard0" / "sum.exr");
    const auto sum1 = fovea::image::readImage(tmp / "shard1" / "sum.exr");
    EXPECT_GT(maxAbsDifference(sum0, sum1), 1e-3) << "two shards traced the same samples";
    merge.insert(merge.end(), {"--out", (tmp / "merged").string()});
    Result m = cli(merge);
    ASSERT_EQ(m.code, 0) << m.describe();
    for (const char* f : {"acc.mean.frame0007.exr", "acc.mean.frame0007.png", "report.json"})
        EXPECT_TRUE(fs::exists(tmp / "merged" / f)) << f;
    const json report = json::parse(readText(tmp / "merged" / "report.json"));
    EXPECT_EQ(report.at("finished"), true);
    EXPECT_EQ(report.at("merged_from").size(), 4u);
    const auto merged = fovea::image::readImage(tmp / "merged" / "acc.mean.frame0007.exr");
    const auto single = fovea::image::readImage(tmp / "single" / "acc.mean.frame0007.exr");
    float peak = 0;
    for (float v : single.pixels) peak = std::max(peak, v);
    // Float rounding of a running mean over 8 frames: a few ulps of the peak. One shard's noise
    // (a shard reusing another's samples) is ~1e-2.
    EXPECT_LE(maxAbsDifference(merged, single), 1e-5 * std::max(1.0f, peak));
}

TEST(CliReferenceShard, FrameShardsMergeToTheSingleRunExactly) {
    TempDir tmp;
    const std::string camera = (kRepo / "graphs" / "cameras" / "cornell_dolly.json").string();
    const std::vector<std::string> path = {"--camera", camera, "--path-frames", "0:4"};
    auto with = [&](std::vector<std::string> more) {
        std::vector<std::string> args = path;
        args.insert(args.end(), more.begin(), more.end());
        return args;
    };
    ASSERT_EQ(reference(path, tmp / "all").code, 0);
    Result a = reference(with({"--frames-of", "1/2"}), tmp / "b");
    ASSERT_EQ(a.code, 0) << a.describe();
    ASSERT_EQ(reference(with({"--frames-of", "0/2"}), tmp / "a").code, 0);
    EXPECT_TRUE(fs::exists(tmp / "a" / "frame0001.exr") &&
                !fs::exists(tmp / "a" / "frame0002.exr"));
    Result m = cli({"merge", (tmp / "b").string(), (tmp / "a").string(), "--out",
                    (tmp / "merged").string(), "--quiet"});
    ASSERT_EQ(m.code, 0) << m.describe();
    for (int f = 0; f <= 4; ++f) {
        const std::string name = "frame000" + std::to_string(f) + ".exr";
        EXPECT_EQ(maxAbsDifference(fovea::image::readImage(tmp / "merged" / name),
                                   fovea::image::readImage(tmp / "all" / name)),
                  0.0)
            << name;
    }
    // Each frame is the converged reference of that path frame, as `--path-frame F` renders it.
    Result one = reference({"--camera", camera, "--path-frame", "3"}, tmp / "three");
    ASSERT_EQ(one.code, 0) << one.describe();
    EXPECT_EQ(maxAbsDifference(fovea::image::readImage(tmp / "three" / "acc.mean.frame0007.exr"),
                               fovea::image::readImage(tmp / "merged" / "frame0003.exr")),
              0.0);
}

TEST(CliReferenceShard, MergeRefusesShardsThatDoNotBelongTogether) {
    TempDir tmp;
    for (int i : {0, 1})
        ASSERT_EQ(
            reference({"--shard", std::to_string(i) + "/2"}, tmp / ("s" + std::to_string(i))).code,
            0);
    const std::string s0 = (tmp / "s0").string(), s1 = (tmp / "s1").string();
    auto merge = [&](std::vector<std::string> dirs, const std::string& out) {
        std::vector<std::string> args = {"merge"};
        args.insert(args.end(), dirs.begin(), dirs.end());
        args.insert(args.end(), {"--out", (tmp / out).string(), "--quiet"});
        return cli(args);
    };
    Result dup = merge({s0, s0}, "dup");
    EXPECT_EQ(dup.code, 2) << dup.describe();
    EXPECT_TRUE(contains(dup.err, "missing shard(s) 1") &&
                contains(dup.err, "duplicate shard(s) 0"))
        << dup.err;
    // Another spp: another reference.
    ASSERT_EQ(cli({"reference", "--spp", "4", "--size", kSize, "--shard", "1/2", "--out",
                   (tmp / "other").string(), "--quiet"})
                  .code,
              0);
    Result other = merge({s0, (tmp / "other").string()}, "other_out");
    EXPECT_EQ(other.code, 2) << other.describe();
    EXPECT_TRUE(contains(other.err, "other/shard.json") && contains(other.err, "/key/"))
        << other.err;
    // An unfinished shard (no shard.json).
    fs::create_directories(tmp / "empty");
    Result empty = merge({s0, (tmp / "empty").string()}, "empty_out");
    EXPECT_EQ(empty.code, 2) << empty.describe();
    EXPECT_TRUE(contains(empty.err, "not a finished reference shard")) << empty.err;
    // A NaN-poisoned sum: exit 1 naming the shard, nothing written.
    auto sum = fovea::image::readImage(tmp / "s1" / "sum.exr");
    sum.pixels[5] = std::nanf("");
    fovea::image::writeExr(tmp / "s1" / "sum.exr", sum);
    Result nan = merge({s0, s1}, "nan_out");
    EXPECT_EQ(nan.code, 1) << nan.describe();
    EXPECT_TRUE(contains(nan.err, "s1/sum.exr") && contains(nan.err, "NaN")) << nan.err;
    EXPECT_FALSE(fs::exists(tmp / "nan_out" / "report.json"));

    // Bad shard requests fail before any rendering.
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"--shard", "2/2"},
          {"--shard", "0/9"},  // 8 frames cannot make 9 shards: shard 0 is empty
          {"--frames-of", "0/2"},
          {"--shard", "0/2", "--path-frames", "0:3"}}) {
        Result r = reference(args, tmp / "bad");
        EXPECT_EQ(r.code, 2) << r.describe();
        EXPECT_TRUE(contains(r.err, args[0])) << r.err;
    }
}
