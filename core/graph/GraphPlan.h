// The compiled form of a graph: what every compile stage reads and writes. CPU-only data, so
// every stage is unit-tested without a GPU; the runtime (RenderGraph) allocates and executes it.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/graph/GraphDesc.h"
#include "core/graph/Pass.h"
#include "core/graph/Reflection.h"

namespace fovea::graph {

constexpr size_t kNone = static_cast<size_t>(-1);

struct PassNode {
    std::string name;
    std::string type;
    std::string pointer;  // "/passes/i" in the graph file
    size_t descIndex = 0;
    std::unique_ptr<Pass> pass;
    Reflection reflection;
    bool alive = true;
    std::string cullReason;  // why it is not alive
};

// Where an input of a pass gets its data.
struct InputSource {
    size_t node = kNone;      // producing node
    std::string field;        // producing output
    uint32_t delay = 0;       // frames of delay (0 = this frame)
    std::string pointer;      // "/edges/i"
    size_t resource = kNone;  // filled by resolveResources
};

enum class Lifetime { Transient, Output, History, Persistent };
const char* lifetimeName(Lifetime l);

struct ResourcePlan {
    std::string name;  // "pass.field"
    size_t producer = kNone;
    std::string field;
    bool isImage = true;
    uint32_t width = 0, height = 0;
    vk::Format format = vk::Format::eUndefined;
    uint64_t bufferBytes = 0;
    // Buffers (FieldDesc): indirect-argument usage, host-visible memory, what the graph writes
    // into it before the pass sees it.
    bool indirect = false;
    bool hostVisible = false;
    BufferInit init = BufferInit::Undefined;
    const void* contents = nullptr;
    Lifetime lifetime = Lifetime::Transient;
    uint32_t ringSize = 1;  // history: max delay + 1
    // Previous frames the producing pass declared (FieldDesc::historyFrames); delay edges that
    // read it may ask for more (ringSize covers both).
    uint32_t declaredHistory = 0;
    int firstUse = -1, lastUse = -1;  // positions in the execution order
    int aliasGroup = -1;
    uint64_t bytes() const;  // estimated size (images: w*h*bytes per pixel)
};

struct AliasGroup {
    uint64_t bytes = 0;           // estimate: the largest member
    std::vector<size_t> members;  // resources, in order of first use
};

struct BarrierPlan {
    int position = 0;                  // before the pass at this order position
    std::vector<size_t> initialize;    // aliased images first written here: UNDEFINED -> GENERAL
    std::vector<std::string> hazards;  // why the barrier exists ("RAW tm.input <- src.color")
};

struct CompileOptions {
    uint32_t width = 256, height = 256;
    uint32_t sceneFeatures = 0;  // SceneFeature bits the loaded scene provides
    bool aliasing = true;
};

struct CompiledPlan {
    std::string file;
    CompileOptions options;
    std::vector<PassNode> nodes;                                   // in graph-file order
    std::map<std::pair<size_t, std::string>, InputSource> inputs;  // (node, input) -> source
    std::vector<std::pair<size_t, size_t>> orderEdges;             // before, after (node indices)
    std::vector<std::pair<size_t, std::string>> outputs;           // marked outputs (node, field)
    std::vector<size_t> order;                                     // alive nodes, execution order
    std::vector<ResourcePlan> resources;
    std::map<std::pair<size_t, std::string>, size_t> resourceOf;  // (node, output/internal)
    std::vector<AliasGroup> aliasGroups;
    std::vector<BarrierPlan> barriers;

    size_t findNode(const std::string& name) const;
    int positionOf(size_t node) const;  // -1 if not ordered (culled)
    uint64_t transientBytes() const;    // with aliasing
    uint64_t transientBytesWithoutAliasing() const;
    uint64_t persistentBytes() const;  // outputs, history rings, persistent
    uint64_t historyBytes() const;     // of which previous-frame slots of history rings
};

}  // namespace fovea::graph
