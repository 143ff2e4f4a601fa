#version 460
// PreviewSamples, step 1: no sample has landed anywhere yet this frame.
#extension GL_GOOGLE_include_directive : require
#include "counts.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform Params { uvec2 size; } pc;

void main() {
    uvec2 p = gl_GlobalInvocationID.xy;
    if (any(greaterThanEqual(p, pc.size))) return;
    counts.texels[p.y * pc.size.x + p.x] = 0u;
}
