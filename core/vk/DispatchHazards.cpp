#include "core/vk/DispatchHazards.h"

#include <algorithm>

#include "core/vk/Barriers.h"

namespace fovea::gpu {

bool DispatchHazards::contains(const std::vector<Key>& set, Key key) {
    return std::find(set.begin(), set.end(), key) != set.end();
}

void DispatchHazards::insert(std::vector<Key>& set, Key key) {
    if (!contains(set, key)) set.push_back(key);
}

void DispatchHazards::beforeDispatch(const vk::raii::CommandBuffer& cmd,
                                     const ComputePipeline& pipeline, vk::Buffer indirectArgs) {
    const auto accesses = pipeline.accesses();
    const Key args{uint64_t(VkBuffer(indirectArgs)), false};
    const bool indirect = bool(indirectArgs);

    bool hazard = indirect && contains(mWritten, args);
    for (const ResourceAccess& a : accesses) {
        const Key key{a.handle, a.image};
        if (contains(mWritten, key) || (a.write && contains(mRead, key))) hazard = true;
    }
    // The indirect-command stage on either side: arguments written by an earlier dispatch, or a
    // write to a buffer an earlier dispatch read as its arguments.
    bool indirectHazard = indirect && contains(mWrittenBeforeIndirect, args);
    for (const ResourceAccess& a : accesses)
        if (a.write && !a.image && contains(mReadIndirect, Key{a.handle, false}))
            indirectHazard = true;
    if (hazard || indirectHazard) {
        if (indirectHazard) {
            computeToIndirectBarrier(cmd);
            mWrittenBeforeIndirect.clear();
            mReadIndirect.clear();
            ++mIndirectBarriers;
        } else {
            computeToComputeBarrier(cmd);
        }
        mWritten.clear();
        mRead.clear();
        ++mBarriers;
    }
    for (const ResourceAccess& a : accesses) {
        const Key key{a.handle, a.image};
        if (a.read) insert(mRead, key);
        if (a.write) {
            insert(mWritten, key);
            if (!key.image) insert(mWrittenBeforeIndirect, key);
        }
    }
    if (indirect) insert(mReadIndirect, args);
    ++mDispatches;
}

}  // namespace fovea::gpu
