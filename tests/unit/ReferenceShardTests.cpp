// The partition of a sharded reference (eval/reference/ReferenceShards.h): shard I of N gets a
// contiguous block of the single run's frames, and the blocks of 0..N-1 are disjoint, in order
// and cover every frame, so no two shards trace the same sample stream (the path tracer's streams
// are a hash of seed, pixel, frame index and sample) and together they trace all of them.
#include <gtest/gtest.h>

#include "core/util/Error.h"
#include "eval/reference/ReferenceShards.h"

using namespace fovea;
using namespace fovea::eval;

TEST(ReferenceShard, BlocksAreDisjointInOrderAndCoverEveryFrame) {
    for (uint32_t total : {0u, 1u, 2u, 7u, 8u, 64u, 1000u, 4000000000u})
        for (uint32_t count : {1u, 2u, 3u, 4u, 7u, 16u, 100u, 65536u}) {
            uint32_t next = 0;
            uint32_t largest = 0, smallest = UINT32_MAX;
            for (uint32_t i = 0; i < count; ++i) {
                const FrameRange r = shardRange({i, count}, total);
                ASSERT_EQ(r.begin, next) << total << " frames, shard " << i << "/" << count;
                ASSERT_LE(r.begin, r.end);
                next = r.end;
                largest = std::max(largest, r.size());
                smallest = std::min(smallest, r.size());
            }
            EXPECT_EQ(next, total) << total << " frames in " << count << " shards";
            EXPECT_LE(largest - smallest, 1u) << "balanced: " << total << "/" << count;
        }
}

TEST(ReferenceShard, ParsesShardsAndRangesNamingTheFlag) {
    EXPECT_EQ(parseShard("0/1", "--shard").count, 1u);
    const Shard s = parseShard("3/4", "--shard");
    EXPECT_EQ(s.index, 3u);
    EXPECT_EQ(s.count, 4u);
    for (const char* bad : {"4/4", "1/0", "a/b", "1", "-1/4", "1/4/2", "", "0/99999"}) {
        try {
            parseShard(bad, "--shard");
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const InputError& e) {
            EXPECT_EQ(e.file(), "--shard") << bad;
        }
    }
    const FrameRange r = parseFrameRange("2:5", "--path-frames");
    EXPECT_EQ(r.begin, 2u);
    EXPECT_EQ(r.end, 6u);
    EXPECT_EQ(parseFrameRange("7:7", "--path-frames").size(), 1u);
    for (const char* bad : {"5:2", "2-5", ":5", "x:y", "1:2:3"})
        EXPECT_THROW(parseFrameRange(bad, "--path-frames"), InputError) << bad;
}
