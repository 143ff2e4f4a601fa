// The moving block grid of seed 003 P2 §6.1: 32x32 blocks whose grid moves every frame by one of
// 16 fixed offsets, so block seams never stay in one place. Shared by every pass that must agree
// on where the blocks are this frame: BMFR fits per block, and VisualPolarWarp's staircase clip
// (P5 §3.3) gives each block column one phi height, synced with these offsets.
#pragma once
#include <array>
#include <cstdint>

namespace fovea::sampling {

inline constexpr int kBlockGridSize = 32;  // P2 §6.1: 32x32 blocks
inline constexpr int kBlockGridOffsetCount = 16;

// P2 §6.1: "a static sequence of 16 random offsets, uniformly distributed over the whole set of
// possible offsets" (drawn once with Python's random.Random(2019), both axes in [0, 32)). Block
// (bx, by) covers pixels [b * 32 - offset, b * 32 - offset + 32) on each axis.
inline constexpr int kBlockGridOffsets[kBlockGridOffsetCount][2] = {
    {9, 15},  {31, 10}, {15, 15}, {20, 18}, {26, 15}, {26, 29}, {4, 20}, {2, 23},
    {23, 21}, {17, 13}, {30, 6},  {6, 10},  {18, 28}, {26, 3},  {11, 7}, {2, 3}};

// The authors' own sequence (Koskela et al.'s OpenCL code, maZZZu/bmfr opencl/bmfr.cl
// BLOCK_OFFSETS, MIT), in the convention above. Their kernel reads image pixel
// gid - 16 + o for block-grid pixel gid, so their offset o in [-16, 14] is ours 16 - o, taken
// modulo 32 (a whole block step only renumbers the blocks). Every entry is even.
inline constexpr int kPublishedBlockGridOffsets[kBlockGridOffsetCount][2] = {
    {30, 30}, {12, 22}, {24, 2},  {8, 16},  {26, 24}, {14, 4}, {4, 28}, {26, 16},
    {4, 2},   {24, 0},  {10, 10}, {18, 18}, {10, 30}, {0, 4},  {2, 20}, {22, 12}};

enum class BlockGridTable { Fovea, Published };

// This frame's block grid offset in pixels, each component in [0, 32).
inline std::array<int, 2> blockGridOffset(uint64_t frame,
                                          BlockGridTable table = BlockGridTable::Fovea) {
    const auto& o = table == BlockGridTable::Published
                        ? kPublishedBlockGridOffsets[frame % kBlockGridOffsetCount]
                        : kBlockGridOffsets[frame % kBlockGridOffsetCount];
    return {o[0], o[1]};
}

}  // namespace fovea::sampling
