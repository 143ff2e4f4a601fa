#version 460
// Unwarp step 2 (seed 003 P5 §3.4): backward mapping. Every screen pixel finds its (rho, phi)
// in its eye's Visual-Polar image and samples it: bilinear in rho between two columns (clamped
// to the edge), in each column bilinear in phi at that column's own height, wrapped (hides the
// phi seam); trilinear across the phi-only mips where one pixel covers several phi rows (the
// fovea). The gaze pixel maps to rho ~ 0, t = 0: finite, never a division by zero.
// The per-pixel (rho, t), mip level and blur sigma come from the persistent `lookup` image, built
// by unwarp_lookup.comp only when the mapping changed (P5 §3.4 precomputes them): this dispatch
// does only the fetches, with no branch around expensive work (llvmpipe runs both sides of a
// divergent branch; docs/passes/Unwarp.md "Cost").
#extension GL_GOOGLE_include_directive : require

#include "../common/camera.glsl"
#define VISUAL_POLAR_PARAMS
#include "../common/visual_polar.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;
#ifdef UNWARP_FINE
layout(rgba32f) uniform readonly image2D mip1;
layout(rgba32f) uniform readonly image2D mip2;
layout(rgba32f) uniform readonly image2D mip3;
// unwarp_lookup.comp's group counts and, per eye, the box of the pixels with L > 0.
layout(std430) readonly buffer unwarp_rebuild {
    uvec4 rebuildGroups;
    uvec4 mipGroups[3];
    uvec4 fineGroups;
    uvec4 fineBox[2];
};
#endif
layout(rgba32f) uniform writeonly image2D unwarped;
layout(rgba32f) uniform writeonly image2D result;
// Per pixel: x rho, y t, z mip level L, w the blur's sigma (P5 §3.5); persistent.
layout(rgba32f) uniform readonly image2D lookup;

layout(push_constant) uniform Params {
    uint levels;    // 1..4
    uint toResult;  // 1: write `result` (no blur follows), 0: `unwarped` for the blur
} pc;

vec4 loadLevel(uint level, ivec2 p) {
#ifdef UNWARP_FINE
    if (level == 0u) return texelFetch(color, p, 0);
    if (level == 1u) return imageLoad(mip1, p);
    if (level == 2u) return imageLoad(mip2, p);
    return imageLoad(mip3, p);
#else
    return texelFetch(color, p, 0);  // level 0 only (the fine dispatch does the rest)
#endif
}

// One column at its own phi height for this level; t wraps.
vec4 columnSample(VisualPolarMap m, uint eye, uint column, float t, uint level) {
    uint n = vpRowsAtLevel(m, column, level);  // >= 1
    float y = fract(t) * float(n) - 0.5;
    float j0f = floor(y);
    float fy = y - j0f;
    int j0 = int(j0f);
    // y is in [-0.5, n - 0.5), so j0 in [-1, n - 1]: the wrap is two selects (an integer `%`
    // costs a scalar division per lane on llvmpipe).
    int a = j0 < 0 ? int(n) - 1 : j0;
    int b = a + 1 >= int(n) ? 0 : a + 1;
    int x = int(eye * m.width + column);
    return mix(loadLevel(level, ivec2(x, a)), loadLevel(level, ivec2(x, b)), fy);
}

vec4 bilinear(VisualPolarMap m, uint eye, vec2 rt, uint level) {
    float x = rt.x * float(m.width) - 0.5;
    float i0f = floor(x);
    float fx = x - i0f;
    int i0 = int(i0f);
    uint c0 = uint(clamp(i0, 0, int(m.width) - 1));
    uint c1 = uint(clamp(i0 + 1, 0, int(m.width) - 1));
    return mix(columnSample(m, eye, c0, rt.y, level), columnSample(m, eye, c1, rt.y, level), fx);
}

// Two dispatches (one pipeline each): the full-screen one samples level 0 only, the fine one
// (indirect, over each eye's box of pixels with L > 0, from unwarp_lookup.comp) redoes those
// pixels trilinearly and overwrites them. At the default reduction that box is the fovea; the
// level choice and the second level's blend cost ~45 % of the full-screen dispatch on llvmpipe,
// which runs both sides of every branch (docs/passes/Unwarp.md "Cost").
void main() {
#ifdef UNWARP_FINE
    uint eye = gl_WorkGroupID.z;
    uvec4 box = fineBox[eye];
    if (box.x > box.z) return;  // this eye has no pixel with L > 0
    ivec2 p = ivec2(box.xy + gl_GlobalInvocationID.xy);
    if (p.x > int(box.z) || p.y > int(box.w)) return;
#else
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(cameraImageSize());
    if (p.x >= size.x || p.y >= size.y) return;
    uint eyes = clamp(vp.grid.z, 1u, 2u);
    uint eye = min(cameraEyeOf(uint(p.x)), eyes - 1u);
#endif
    VisualPolarMap m = vpMapOfEye(eye);
    vec4 lk = imageLoad(lookup, p);
    vec2 rt = lk.xy;
#ifdef UNWARP_FINE
    float L = lk.z;
    uint l0 = uint(floor(L));
    uint l1 = min(l0 + 1u, max(pc.levels, 1u) - 1u);
    vec4 c = bilinear(m, eye, rt, l0);
    // Only where level l1 has a weight (L is 0 exactly outside the box).
    float fl = L - float(l0);
    if (l1 != l0 && fl > 0.0) c = mix(c, bilinear(m, eye, rt, l1), fl);
#else
    vec4 c = bilinear(m, eye, rt, 0u);
#endif
    // NaN/Inf in the VP image never reach the screen.
    if (any(isnan(c)) || any(isinf(c))) c = vec4(0.0);
    if (pc.toResult != 0u) imageStore(result, p, c);
    else imageStore(unwarped, p, c);
}
