// GPU timestamps for per-pass timing (vkCmdWriteTimestamp2 into one query pool).
#pragma once
#include <cstdint>
#include <vector>
#include <vulkan/vulkan_raii.hpp>

namespace fovea::gpu {

class Context;

class TimestampPool {
public:
    // Throws RuntimeError when the context's queue cannot write timestamps.
    TimestampPool(const Context& context, uint32_t capacity);

    uint32_t capacity() const { return mCapacity; }
    // vkCmdResetQueryPool for all queries; record before the first write of a submission.
    void reset(const vk::raii::CommandBuffer& cmd);
    // vkCmdWriteTimestamp2 at ALL_COMMANDS: the tick is taken once all earlier commands finish.
    void write(const vk::raii::CommandBuffer& cmd, uint32_t index);
    // Ticks of queries [0, count) after the submission finished (waits for the results).
    // Masked to the queue's timestampValidBits so differences stay meaningful on wraparound.
    // Throws RuntimeError if one of them was not recorded since the last reset: waiting on a
    // query that is never written would hang forever.
    std::vector<uint64_t> readTicks(uint32_t count) const;
    double ticksToMs(uint64_t ticks) const;

private:
    vk::raii::QueryPool mPool = nullptr;
    uint32_t mCapacity = 0;
    std::vector<bool> mRecorded;  // written since the last reset, as recorded on the host
    uint64_t mValidMask = ~0ull;
    double mPeriodNs = 1.0;
};

}  // namespace fovea::gpu
