#version 460
// ATrousNH's tile lists (seed 000 §3.4, Algorithm 1: "each iteration in a layer reconstructs only
// the area corresponding to that layer"): which 8x8 tiles (one atrous_nh.comp workgroup each)
// hold pixels of which foveation layers, so a level dispatches only the tiles it changes instead
// of the whole screen. Built from the FoveationMask layer ids on the GPU (no read-back) and kept
// while the mask is unchanged (once per gaze). For each key k = 1..7 (a set of layers, bit l =
// layer l) list k holds every tile containing a pixel of a layer in k; tileArgs[k] is its
// indirect dispatch (x, y, 1) with the count in .w. Modes:
//  0: reset (one workgroup): every count 0;
//  1: build (one workgroup per tile): append the tile to each requested list it belongs to;
//  2: finalize (one workgroup): counts -> group counts, x <= kMaxGroupsX (x * y >= count, the
//     surplus groups of the last row return at once in atrous_nh.comp).
layout(local_size_x = 8, local_size_y = 8) in;

layout(r32ui) uniform readonly uimage2D mask;
layout(std430) buffer atrous_tiles {
    uvec4 tileArgs[8];  // per key: VkDispatchIndirectCommand (x, y, z) + tile count
    uint tileIds[];     // key k's tiles at [k * tileStride, ...), packed x | y << 16
};

layout(push_constant) uniform Params {
    ivec2 size;
    int layerCount;  // 1..3; mask layer ids >= layerCount count as the last layer
    int mode;
    int tileStride;  // tiles in the image (capacity of one list)
    int keys;        // bit k: build list k (the keys the pass's schedule uses)
} pc;

// Vulkan guarantees maxComputeWorkGroupCount[0] >= 65535.
const uint kMaxGroupsX = 65535u;

shared uint tileLayers;

void main() {
    uint lane = gl_LocalInvocationIndex;
    if (pc.mode == 0) {
        if (lane < 8u) tileArgs[lane] = uvec4(0u, 0u, 1u, 0u);
        return;
    }
    if (pc.mode == 2) {
        if (lane < 8u) {
            uint n = tileArgs[lane].w;
            uint x = min(n, kMaxGroupsX);
            uint y = (n + kMaxGroupsX - 1u) / kMaxGroupsX;  // constant divisor, n = 0 gives 0
            tileArgs[lane].xyz = uvec3(x, y, 1u);
        }
        return;
    }
    if (lane == 0u) tileLayers = 0u;
    barrier();
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(p, pc.size))) {
        // Same layer rule as atrous_nh.comp's layerOf().
        uint layer = min((imageLoad(mask, p).r >> 1) & 3u, uint(pc.layerCount - 1));
        atomicOr(tileLayers, 1u << layer);
    }
    barrier();
    // Lanes 1..7 append the tile to lists 1..7 (every tile has an in-image pixel, the grid is
    // ceil(size / 8), so tileLayers != 0).
    uint key = lane;
    if (key >= 1u && key < 8u && ((pc.keys >> key) & 1) != 0 && (tileLayers & key) != 0u) {
        uint slot = atomicAdd(tileArgs[key].w, 1u);
        tileIds[key * uint(pc.tileStride) + slot] = gl_WorkGroupID.x | (gl_WorkGroupID.y << 16);
    }
}
