#version 460
// HistoryFix: mip level 1 = 2x2 averages over the pixels that have a surface (depth > 0), per
// eye; a = their mean view depth (0 = no surface in the block). Seed 004 builds the HistoryFix
// mips from the accumulated signal; colour is sanitized so a NaN cannot spread to a block. With
// `albedo` / `emission` connected the blocks average the demodulated colour, with `normal` connected
// nmip1 gets the blocks' mean normal (mip_common.glsl).
#extension GL_GOOGLE_include_directive : require
#include "common/color.glsl"
#include "history_fix/mip_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;
uniform sampler2D depth;
uniform sampler2D albedo;    // optional (useAlbedo)
uniform sampler2D emission;  // optional (useEmission)
uniform sampler2D normal;    // optional (useNormal)
layout(rgba32f) uniform writeonly image2D mip1;
layout(rgba16f) uniform writeonly image2D nmip1;  // mean normal of the same pixels (useNormal)

layout(push_constant) uniform Params {
    ivec2 size;    // full-resolution image
    int eyeWidth;  // >= 1
    int eyes;
    int blocks;    // blocks per eye at this level
    int height;    // rows of this level
    int useAlbedo;
    int useEmission;
    int useNormal;
} pc;

void main() {
    ivec2 b = ivec2(gl_GlobalInvocationID.xy);
    if (b.x >= pc.blocks * pc.eyes || b.y >= pc.height || any(greaterThanEqual(b, imageSize(mip1))))
        return;
    int eye = b.x / pc.blocks;  // blocks >= 1
    int x0 = eye * pc.eyeWidth;
    int x1 = eye == pc.eyes - 1 ? pc.size.x - 1 : x0 + pc.eyeWidth - 1;
    ivec2 base = ivec2(x0 + 2 * (b.x - eye * pc.blocks), 2 * b.y);
    vec4 sum = vec4(0.0);
    vec3 nsum = vec3(0.0);
    float count = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 q = base + ivec2(k & 1, k >> 1);
        if (q.x > x1 || q.y >= pc.size.y) continue;
        float z = texelFetch(depth, q, 0).r;
        if (!(z > 0.0) || isinf(z)) continue;
        vec3 c = sanitize(texelFetch(color, q, 0)).rgb;
        if (pc.useAlbedo != 0 || pc.useEmission != 0) {
            vec3 e = hfSafeEmission(texelFetch(emission, q, 0).rgb, pc.useEmission != 0);
            c = (c - e) / hfSafeAlbedo(texelFetch(albedo, q, 0).rgb, pc.useAlbedo != 0);  // >= 1e-3
        }
        sum += vec4(c, z);
        if (pc.useNormal != 0) {
            vec3 n = texelFetch(normal, q, 0).xyz;
            nsum += any(isnan(n)) || any(isinf(n)) ? vec3(0.0) : n;  // 0: no vote
        }
        count += 1.0;
    }
    imageStore(mip1, b, count > 0.0 ? sum / count : vec4(0.0));
    if (pc.useNormal != 0) imageStore(nmip1, b, vec4(count > 0.0 ? nsum / count : vec3(0.0), 0.0));
}
