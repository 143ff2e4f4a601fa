#version 460
// HistoryFix: mip level L from level L-1, 2x2 averages over the children with a surface (a > 0),
// per eye (see mip_common.glsl). a = mean view depth, 0 = no surface below the texel. With
// useNormal the mean normals (nsrc -> ndst) are averaged over the same children.
#extension GL_GOOGLE_include_directive : require
#include "history_fix/mip_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D src;
uniform sampler2D nsrc;  // mean normals of level L-1 (useNormal)
layout(rgba32f) uniform writeonly image2D dst;
layout(rgba16f) uniform writeonly image2D ndst;

layout(push_constant) uniform Params {
    int eyes;
    int blocks;     // blocks per eye at this level
    int height;     // rows of this level
    int srcBlocks;  // blocks per eye at level L-1
    int srcHeight;
    int useNormal;
} pc;

void main() {
    ivec2 b = ivec2(gl_GlobalInvocationID.xy);
    if (b.x >= pc.blocks * pc.eyes || b.y >= pc.height || any(greaterThanEqual(b, imageSize(dst))))
        return;
    int eye = b.x / pc.blocks;  // blocks >= 1
    ivec2 base = ivec2(2 * (b.x - eye * pc.blocks), 2 * b.y);
    vec4 sum = vec4(0.0);
    vec3 nsum = vec3(0.0);
    float count = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 q = base + ivec2(k & 1, k >> 1);
        if (q.x >= pc.srcBlocks || q.y >= pc.srcHeight) continue;  // outside the eye's blocks
        ivec2 t = ivec2(eye * pc.srcBlocks + q.x, q.y);
        vec4 v = texelFetch(src, t, 0);
        if (!(v.a > 0.0)) continue;
        sum += v;
        if (pc.useNormal != 0) nsum += texelFetch(nsrc, t, 0).xyz;
        count += 1.0;
    }
    imageStore(dst, b, count > 0.0 ? sum / count : vec4(0.0));
    if (pc.useNormal != 0) imageStore(ndst, b, vec4(count > 0.0 ? nsum / count : vec3(0.0), 0.0));
}
