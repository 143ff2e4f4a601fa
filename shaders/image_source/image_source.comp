#version 460
// ImageSource: constant, gradient, seeded noise or frame-index images for tests and pipelines.
#extension GL_GOOGLE_include_directive : require
#include "common/random.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f) uniform writeonly image2D color;

layout(push_constant) uniform Params {
    vec4 value;
    ivec2 size;
    int pattern;  // 0 constant, 1 gradient, 2 noise, 3 frame index
    uint seed;
    uint frame;
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    vec4 c = pc.value;
    if (pc.pattern == 1) {
        // size >= 1 on both axes (the graph never resolves an empty image), so no division by 0.
        vec2 uv = (vec2(p) + 0.5) / vec2(pc.size);
        c = vec4(uv.x, uv.y, 1.0 - uv.x, 1.0) * pc.value;
    } else if (pc.pattern == 2) {
        uint h = hashCombine(hashCombine(pc.seed, uint(p.x)), uint(p.y));
        c = vec4(uintToUnitFloat(h), uintToUnitFloat(pcgHash(h)), uintToUnitFloat(pcgHash(h + 1u)), 1.0) * pc.value;
    } else if (pc.pattern == 3) {
        c = vec4(float(pc.frame)) * pc.value;
    }
    imageStore(color, p, c);
}
