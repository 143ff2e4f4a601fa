#version 460
// InvertPass: result = white - color (RGB), alpha kept. Includes fovea's common GLSL from the
// installed shader folder.
#extension GL_GOOGLE_include_directive : require
#include "common/color.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;
layout(rgba32f) uniform writeonly image2D result;

layout(push_constant) uniform Params {
    ivec2 size;
    float white;
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    vec4 c = texelFetch(color, p, 0);
    imageStore(result, p, sanitize(vec4(vec3(pc.white) - c.rgb, c.a)));
}
