#version 460
// HmdPreview: mip level l of the equirect image from level l - 1 (2x2 box; at an odd edge the
// last column wraps to the first - the longitude is periodic - and the last row repeats). Levels
// >= 1 live side by side in the `mips` image (HmdPreviewPass.cpp), level 0 is the input.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D equirect;
layout(rgba32f) uniform image2D mips;

layout(push_constant) uniform Params {
    ivec2 dstSize, srcSize;  // >= 1 each
    int dstOffset, srcOffset;
    int fromInput;  // 1: level 1, read the input; else level l - 1 of `mips`
} pc;

vec4 source(ivec2 q) {
    q.x = q.x % pc.srcSize.x;           // wrap in longitude (q.x >= 0)
    q.y = min(q.y, pc.srcSize.y - 1);   // clamp at the pole
    return pc.fromInput != 0 ? texelFetch(equirect, q, 0)
                             : imageLoad(mips, ivec2(q.x + pc.srcOffset, q.y));
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.dstSize))) return;
    ivec2 b = 2 * p;
    vec4 sum = source(b) + source(b + ivec2(1, 0)) + source(b + ivec2(0, 1)) + source(b + ivec2(1));
    imageStore(mips, ivec2(p.x + pc.dstOffset, p.y), 0.25 * sum);
}
