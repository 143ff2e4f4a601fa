// The device side of one plan resource (private to RenderGraph*.cpp).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/vk/Resources.h"

namespace fovea::graph {

struct RuntimeResource {
    std::string key;  // identity for keeping history rings across rebuilds
    std::vector<std::unique_ptr<gpu::Image>> ring;  // 1 image, or delay+1 for history
    std::unique_ptr<gpu::Buffer> buffer;
    uint64_t version = 0;  // bumped whenever the producer writes it (drives caching)
    // Frame index at allocation: a ring allocated by a rebuild holds no frame from before it, so
    // a read d frames back is valid only from createdAt + d on (kept rings keep their value).
    uint64_t createdAt = 0;
};

}  // namespace fovea::graph
