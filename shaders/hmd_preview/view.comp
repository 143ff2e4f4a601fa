#version 460
// HmdPreview: each pixel of the HMD image looks through the viewport (hmd_viewport.glsl) into
// the equirect image. Trilinear: the footprint of the pixel in level-0 texels (from the uv of its
// right and lower neighbours, the longitude difference wrapped) picks the level, log2 of its
// longer side, as a GPU's mip selection would; near the poles one pixel spans many texels along
// the longitude and a coarser level averages them instead of aliasing (P4 §4).
#extension GL_GOOGLE_include_directive : require
#include "../common/camera.glsl"
#include "../common/hmd_viewport.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D equirect;
layout(rgba32f) uniform readonly image2D mips;
layout(rgba32f) uniform writeonly image2D view;

layout(push_constant) uniform Params {
    ivec2 size;      // output (eyes side by side)
    int eyeWidth;    // >= 1
    ivec2 srcSize;   // equirect level 0, >= 1 each
    int levels;      // mip levels >= 1 available (0: bilinear/nearest only)
    int filterMode;  // 0 nearest, 1 bilinear, 2 trilinear
    int headFollowsGaze;
    float tanHalfFov;
    float aspect;
} pc;

ivec2 levelSize(int l) { return max(pc.srcSize >> l, ivec2(1)); }

int levelOffset(int l) {  // x of level l >= 1 in `mips`
    int o = 0;
    for (int k = 1; k < l; ++k) o += levelSize(k).x;
    return o;
}

// Texel q of level l, whose texels start at column `offset` of `mips` (levelOffset; level 0 is
// the input itself).
vec4 texel(int l, int offset, ivec2 q) {
    ivec2 s = levelSize(l);
    q.x = ((q.x % s.x) + s.x) % s.x;  // the longitude wraps (both signs)
    q.y = clamp(q.y, 0, s.y - 1);
    return l == 0 ? texelFetch(equirect, q, 0) : imageLoad(mips, ivec2(q.x + offset, q.y));
}

vec4 bilinear(int l, vec2 uv) {
    int offset = l == 0 ? 0 : levelOffset(l);  // once for the four taps
    vec2 p = uv * vec2(levelSize(l)) - 0.5;
    vec2 i = floor(p), f = p - i;
    ivec2 q = ivec2(i);
    return mix(mix(texel(l, offset, q), texel(l, offset, q + ivec2(1, 0)), f.x),
               mix(texel(l, offset, q + ivec2(0, 1)), texel(l, offset, q + ivec2(1, 1)), f.x),
               f.y);
}

vec2 uvThrough(vec3 head, vec2 pixel) {
    vec2 ndc = vec2(2.0 * pixel.x / float(pc.eyeWidth) - 1.0,
                    1.0 - 2.0 * pixel.y / float(pc.size.y));
    return cameraEquirectUv(hmdViewportDirection(head, ndc, pc.tanHalfFov, pc.aspect));
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    vec3 head = pc.headFollowsGaze != 0 ? cameraEquirectDirection(camera_info.eyes[0].gaze.xy)
                                        : vec3(0.0, 0.0, -1.0);
    vec2 local = vec2(p.x % pc.eyeWidth, p.y) + 0.5;  // every eye sees the same 360° image
    vec2 uv = uvThrough(head, local);
    vec4 c;
    if (pc.filterMode == 0) {
        c = texel(0, 0, ivec2(floor(uv * vec2(pc.srcSize))));
    } else if (pc.filterMode == 1 || pc.levels == 0) {
        c = bilinear(0, uv);
    } else {
        vec2 dx = uvThrough(head, local + vec2(1.0, 0.0)) - uv;
        vec2 dy = uvThrough(head, local + vec2(0.0, 1.0)) - uv;
        dx.x -= round(dx.x);  // across the seam u jumps by 1: take the short way round
        dy.x -= round(dy.x);
        vec2 s = vec2(pc.srcSize);
        float footprint = max(length(dx * s), length(dy * s));
        // log2 of at least 1 texel: level 0 for magnification (footprint < 1).
        float lod = clamp(log2(max(footprint, 1.0)), 0.0, float(pc.levels));
        int l0 = int(floor(lod));
        int l1 = min(l0 + 1, pc.levels);
        c = mix(bilinear(l0, uv), bilinear(l1, uv), lod - float(l0));
    }
    imageStore(view, p, c);
}
