#include "core/vk/Timestamps.h"

#include "core/util/Error.h"
#include "core/vk/Context.h"

namespace fovea::gpu {

TimestampPool::TimestampPool(const Context& context, uint32_t capacity)
    : mCapacity(capacity), mPeriodNs(context.timestampPeriodNs()) {
    if (capacity == 0) throw RuntimeError("timestamp pool needs a capacity of at least 1");
    auto families = context.physicalDevice().getQueueFamilyProperties();
    const uint32_t bits = families.at(context.queueFamily()).timestampValidBits;
    if (bits == 0)
        throw RuntimeError("'" + context.deviceName() +
                           "' cannot write timestamps on its compute queue");
    mValidMask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
    mPool = vk::raii::QueryPool(
        context.device(),
        vk::QueryPoolCreateInfo{.queryType = vk::QueryType::eTimestamp, .queryCount = capacity});
}

void TimestampPool::reset(const vk::raii::CommandBuffer& cmd) {
    cmd.resetQueryPool(*mPool, 0, mCapacity);
    mRecorded.assign(mCapacity, false);
}

void TimestampPool::write(const vk::raii::CommandBuffer& cmd, uint32_t index) {
    if (index >= mCapacity)
        throw RuntimeError("timestamp index " + std::to_string(index) + " out of range (capacity " +
                           std::to_string(mCapacity) + ")");
    if (mRecorded.empty())
        throw RuntimeError("timestamp pool: reset() must be recorded before write()");
    cmd.writeTimestamp2(vk::PipelineStageFlagBits2::eAllCommands, *mPool, index);
    mRecorded[index] = true;
}

std::vector<uint64_t> TimestampPool::readTicks(uint32_t count) const {
    if (count > mCapacity)
        throw RuntimeError("reading " + std::to_string(count) + " timestamps from a pool of " +
                           std::to_string(mCapacity));
    if (count == 0) return {};
    for (uint32_t i = 0; i < count; ++i)
        if (mRecorded.empty() || !mRecorded[i])
            throw RuntimeError("timestamp " + std::to_string(i) +
                               " was not written since the pool was last reset");
    auto [result, ticks] =
        mPool.getResults<uint64_t>(0, count, count * sizeof(uint64_t), sizeof(uint64_t),
                                   vk::QueryResultFlagBits::e64 | vk::QueryResultFlagBits::eWait);
    if (result != vk::Result::eSuccess)
        throw RuntimeError("timestamp query results not available: " + vk::to_string(result));
    for (auto& t : ticks) t &= mValidMask;
    return ticks;
}

double TimestampPool::ticksToMs(uint64_t ticks) const {
    return static_cast<double>(ticks) * mPeriodNs * 1e-6;
}

}  // namespace fovea::gpu
