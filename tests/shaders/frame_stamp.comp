#version 460
// Test shader of tests/graph/HistoryTests.cpp: writes this frame's stamp and copies what the
// graph hands it as the previous frames (prev_stamp, prev2_stamp) into plain outputs, or -1 when
// the pass was told that history is invalid.
layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f) uniform writeonly image2D stamp;
layout(rgba32f) uniform readonly image2D prev_stamp;
#if KEEP2
layout(rgba32f) uniform readonly image2D prev2_stamp;
#endif
layout(rgba32f) uniform writeonly image2D seen1;
layout(rgba32f) uniform writeonly image2D seen2;

layout(push_constant) uniform Params {
    ivec2 size;
    float stampValue;
    int valid1;
    int valid2;
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    imageStore(stamp, p, vec4(pc.stampValue, float(p.x), float(p.y), 1.0));
    imageStore(seen1, p, pc.valid1 != 0 ? imageLoad(prev_stamp, p) : vec4(-1.0));
#if KEEP2
    imageStore(seen2, p, pc.valid2 != 0 ? imageLoad(prev2_stamp, p) : vec4(-1.0));
#else
    imageStore(seen2, p, vec4(-1.0));
#endif
}
