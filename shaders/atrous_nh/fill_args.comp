#version 460
// ATrousNH's GPU-driven hole filling (one invocation): turns the hole count of the previous level
// into the group count of the next fill level, so fill levels cost nothing once every pixel has a
// value and no CPU read-back is needed. Modes:
//  0: reset the counters (start of the frame);
//  1: fill level: fullGroups if the previous level left a hole, else 0; count executed levels;
//  2: copy-back: fullGroups if an odd number of fill levels ran (result left in ping), else 0.
layout(local_size_x = 1) in;

layout(std430) buffer atrous_fill {
    uvec4 fillArgs;  // VkDispatchIndirectCommand (x, y, z) + padding
    uvec4 copyArgs;
    uint holes;
    uint executed;
};

layout(push_constant) uniform Params {
    int mode;
    ivec2 fullGroups;
} pc;

void main() {
    uvec4 full = uvec4(uvec2(pc.fullGroups), 1u, 0u);
    if (pc.mode == 0) {
        holes = 0u;
        executed = 0u;
    } else if (pc.mode == 1) {
        bool run = holes > 0u;
        fillArgs = run ? full : uvec4(0u);
        executed += run ? 1u : 0u;
        holes = 0u;  // the level that runs counts the holes it leaves
    } else {
        copyArgs = (executed & 1u) != 0u ? full : uvec4(0u);
    }
}
