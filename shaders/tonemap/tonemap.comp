#version 460
// Tonemap: HDR linear -> display-referred 8-bit (exposure, operator, sRGB encoding).
#extension GL_GOOGLE_include_directive : require
#include "common/color.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;
layout(rgba8) uniform writeonly image2D ldr;

layout(push_constant) uniform Params {
    ivec2 size;
    float exposureScale;  // 2^exposure, computed on the CPU
    int op;               // 0 clamp, 1 reinhard, 2 aces
    int srgb;
} pc;

// Narkowicz 2015 ACES filmic fit; denominator >= 0.14 for x >= 0, so no division by zero.
vec3 aces(vec3 x) {
    x = max(x, vec3(0.0));
    return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    vec4 c = sanitize(texelFetch(color, p, 0));
    vec3 x = max(c.rgb * pc.exposureScale, vec3(0.0));
    if (pc.op == 1) x = x / (1.0 + x);  // 1 + x >= 1 since x >= 0
    else if (pc.op == 2) x = aces(x);
    if (pc.srgb != 0) x = linearToSrgb(x);
    imageStore(ldr, p, vec4(clamp(x, 0.0, 1.0), clamp(c.a, 0.0, 1.0)));
}
