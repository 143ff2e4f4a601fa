#version 460
// Remodulate: result = color * albedo' + emission, the inverse of PathTrace's demodulation
// (demodulated = (radiance - emission) / albedo'; albedo' = albedo > eps ? albedo : 1 per
// channel, so near-black albedo is neither divided nor multiplied).
#extension GL_GOOGLE_include_directive : require
#include "common/color.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;
uniform sampler2D albedo;
uniform sampler2D emission;
layout(rgba32f) uniform writeonly image2D result;

layout(push_constant) uniform Params {
    ivec2 size;
    float albedoEpsilon;
    int useEmission;
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    vec4 c = texelFetch(color, p, 0);
    vec3 alb = texelFetch(albedo, p, 0).rgb;
    vec3 safeAlbedo = mix(vec3(1.0), alb, greaterThan(alb, vec3(pc.albedoEpsilon)));
    vec3 rgb = c.rgb * safeAlbedo;
    if (pc.useEmission != 0) rgb += texelFetch(emission, p, 0).rgb;
    imageStore(result, p, sanitize(vec4(rgb, c.a)));
}
