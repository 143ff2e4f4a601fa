#version 460
// Combine: result = weightA * a + weightB * b (b optional, e.g. a delayed history or a reference;
// weights (1, -1) give a difference image).
#extension GL_GOOGLE_include_directive : require
#include "common/color.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D a;
uniform sampler2D b;
layout(rgba32f) uniform writeonly image2D result;

layout(push_constant) uniform Params {
    ivec2 size;
    float weightA;
    float weightB;
    int useB;  // b connected and, for a delayed edge, its history valid
    int absolute;
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    vec4 r = pc.weightA * texelFetch(a, p, 0);
    if (pc.useB != 0) r += pc.weightB * texelFetch(b, p, 0);
    if (pc.absolute != 0) r = abs(r);
    imageStore(result, p, sanitize(r));
}
