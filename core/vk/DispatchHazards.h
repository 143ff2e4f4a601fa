// The barriers between the dispatches of one pass, derived from what each dispatch binds (the
// graph orders passes; this orders the dispatches inside one). A pass records its dispatches
// through ExecuteContext::dispatch, which asks this tracker first, and records no barrier itself
// (docs/architecture.md "The pass contract").
//
// Hazards are per resource (a VkImageView or VkBuffer, whole): a dispatch that reads or writes a
// resource an earlier dispatch wrote (read/write after write), or writes one an earlier dispatch
// read (write after read), waits for it. A dispatch whose indirect arguments an earlier dispatch
// wrote waits at the indirect-command stage too, and so does a write to a buffer an earlier
// dispatch read its arguments from. Independent dispatches get no barrier.
#pragma once
#include <cstdint>
#include <vector>
#include <vulkan/vulkan_raii.hpp>

#include "core/vk/ComputePipeline.h"

namespace fovea::gpu {

class DispatchHazards {
public:
    // Records the barrier (if any) that `pipeline`'s next dispatch needs against the dispatches
    // recorded before it, then notes its accesses. `indirectArgs`: the buffer a dispatchIndirect
    // reads its group counts from (null for a direct dispatch).
    void beforeDispatch(const vk::raii::CommandBuffer& cmd, const ComputePipeline& pipeline,
                        vk::Buffer indirectArgs = nullptr);

    uint64_t dispatches() const { return mDispatches; }
    uint64_t barriers() const { return mBarriers; }
    uint64_t indirectBarriers() const {
        return mIndirectBarriers;
    }  // of barriers(): with the
       // indirect-command stage

private:
    struct Key {
        uint64_t handle;
        bool image;
        bool operator==(const Key&) const = default;
    };
    static bool contains(const std::vector<Key>& set, Key key);
    static void insert(std::vector<Key>& set, Key key);

    std::vector<Key> mWritten;  // since the last barrier
    std::vector<Key> mRead;     // since the last barrier
    // Written since the last barrier that reached the indirect-command stage: a compute-only
    // barrier makes a write visible to shaders, not to vkCmdDispatchIndirect.
    std::vector<Key> mWrittenBeforeIndirect;
    // Read as indirect arguments since the last indirect barrier (a later write waits for them).
    std::vector<Key> mReadIndirect;
    uint64_t mDispatches = 0;
    uint64_t mBarriers = 0;
    uint64_t mIndirectBarriers = 0;
};

}  // namespace fovea::gpu
