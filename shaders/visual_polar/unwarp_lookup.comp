#version 460
// Unwarp's per-pixel sampling positions (seed 003 P5 §3.4: "precomputed" per gaze and size):
// rho, t, mip level and the blur's sigma (P5 §3.5) of every screen pixel, in the persistent
// `lookup` image. mode 0 (one thread) compares the mapping key (the `vp` block, the field of view,
// the level count and the blur profile) with the one `lookup_key` holds, stores the new key and
// writes the group counts of the rebuild: all groups when it changed (or the cache is off), none
// otherwise.
// mode 1 is that rebuild, dispatched indirectly, so a frame with an unchanged key runs none of
// this math (on lavapipe a per-pixel `if (stale)` would: llvmpipe executes both sides of a
// branch under a lane mask; docs/passes/Unwarp.md "Cost"). The rebuild also grows each eye's box
// of pixels with L > 0; mode 2 (one thread, every frame) turns the boxes into the group counts of
// unwarp.comp's fine dispatch and of the phi mip levels (only the columns the fine dispatch
// reads; none for a level it never reads, phi_mip_levels.glsl).
#extension GL_GOOGLE_include_directive : require

#include "../common/camera.glsl"
#define VISUAL_POLAR_PARAMS
#include "../common/visual_polar.glsl"
#include "phi_mip_levels.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// Per pixel: x rho, y t, z mip level L, w the blur's sigma (P5 §3.5); persistent.
layout(rgba32f) uniform writeonly image2D lookup;
layout(std430) buffer LookupKey { uvec4 key[5]; } lookup_key;
// VkDispatchIndirectCommands (x, y, z, padding), pass-owned with INDIRECT usage: the mode-1
// rebuild, phi_mips.comp's levels 1..3 and unwarp.comp's fine dispatch; then, per eye, the box
// (min x, min y, max x, max y; screen pixels) of the pixels whose level L is above 0, which only
// the fine dispatch samples (the full-screen one reads level 0 alone), and the highest VP column
// those pixels read (the phi mips are built up to it).
layout(std430) buffer unwarp_rebuild {
    uvec4 rebuildGroups;
    uvec4 mipGroups[3];
    uvec4 fineGroups;
    uvec4 fineBox[2];
    uint fineColumn[2];
};

layout(push_constant) uniform Params {
    uint levels;        // 1..4
    float sigmaMax;     // blur sigma (pixels) at blurDegrees for this height
    float blurDegrees;  // >= 1
    uint useCache;      // 0: rebuild every frame (benchmarks, tests)
    uint mode;          // 0: key check (one thread), 1: rebuild, 2: fine groups (one thread)
    uint groupsX;       // the rebuild's group counts when it runs
    uint groupsY;
    uint mipGroupsY;    // phi_mips.comp's row groups for a level it builds
} pc;

// Everything the lookup depends on besides the output size (a resize recompiles the pass).
uvec4 mappingKey(int k) {
    if (k == 0) return vp.grid;
    if (k == 1) return floatBitsToUint(vp.fovea);
    if (k == 2) return floatBitsToUint(vp.eyes[0]);
    if (k == 3) return floatBitsToUint(vp.eyes[1]);
    return floatBitsToUint(vec4(camera_info.jitter.zw, pc.sigmaMax, pc.blurDegrees)) ^
           uvec4(0u, 0u, 0u, pc.levels << 16);
}

// View-space direction through a point of an eye image (camera.glsl's cameraRay convention).
vec3 viewDirection(vec2 local) {
    vec2 size = vec2(max(cameraEyeSize(), uvec2(1u)));
    vec2 ndc = vec2(2.0 * local.x / size.x - 1.0, 1.0 - 2.0 * local.y / size.y);
    float t = camera_info.jitter.z;
    return vec3(ndc.x * t * camera_info.jitter.w, ndc.y * t, -1.0);
}

// Angle in degrees between two view directions (atan form: accurate for small angles).
float angleDegrees(vec3 a, vec3 b) { return degrees(atan(length(cross(a, b)), dot(a, b))); }

// P5 §3.5: 0 inside the fovea, linear in the eccentricity (degrees) from the fovea's edge to
// sigmaMax at blurDegrees, clamped beyond (ours).
float sigmaAt(VisualPolarMap m, vec2 local) {
    vec2 d = local - m.gaze;
    float r = length(d);
    float rFovea = m.dMax * m.foveaDegrees / kVpMaxDegrees;
    if (r <= rFovea) return 0.0;
    vec3 g = viewDirection(m.gaze);
    float e = angleDegrees(viewDirection(local), g);
    float eEdge = angleDegrees(viewDirection(m.gaze + d * (rFovea / r)), g);  // r > rFovea >= 0
    // A fovea wider than blurDegrees: full sigma right outside it.
    float span = max(pc.blurDegrees - eEdge, 1e-3);
    return pc.sigmaMax * clamp((e - eEdge) / span, 0.0, 1.0);
}

void main() {
    if (pc.mode == 0u) {
        if (gl_GlobalInvocationID.xy != uvec2(0u)) return;
        bool stale = pc.useCache == 0u;
        for (int k = 0; k < 5; ++k) {
            uvec4 key = mappingKey(k);
            stale = stale || any(notEqual(lookup_key.key[k], key));
            lookup_key.key[k] = key;
        }
        rebuildGroups = stale ? uvec4(pc.groupsX, pc.groupsY, 1u, 0u) : uvec4(0u, 0u, 1u, 0u);
        // The rebuild grows the boxes and columns again from empty (min > max).
        if (stale) {
            fineBox[0] = fineBox[1] = uvec4(0xffffffffu, 0xffffffffu, 0u, 0u);
            fineColumn[0] = fineColumn[1] = 0u;
        }
        return;
    }
    if (pc.mode == 2u) {
        if (gl_GlobalInvocationID.xy != uvec2(0u)) return;
        // One group count for both eyes (z = eye): the larger box; an empty box is 0 groups.
        uvec2 extent = uvec2(0u);
        for (uint e = 0u; e < 2u; ++e)
            if (fineBox[e].x <= fineBox[e].z)
                extent = max(extent, fineBox[e].zw - fineBox[e].xy + 1u);
        // Clamped to the image: group counts never come from memory the rebuild did not write
        // (a bug there would otherwise be a dispatch of billions of groups).
        uvec2 groups = (min(extent, cameraImageSize()) + 7u) / 8u;  // local size 8 x 8
        uint eyes = clamp(vp.grid.z, 1u, 2u);
        bool fine = all(greaterThan(groups, uvec2(0u)));
        fineGroups = fine ? uvec4(groups, eyes, 0u) : uvec4(0u, 0u, 1u, 0u);
        // P5 §3.4: the phi mips only where the fine dispatch reads them (columns 0 up to the
        // highest it reads, per eye: z = eye) and no dispatch for a level it never reads (at
        // reduction 0.61 and a centre gaze only level 1, in the fovea's columns); pc.levels
        // bounds the C++ loop.
        uint columns = min(max(fineColumn[0], eyes > 1u ? fineColumn[1] : 0u) + 1u, vp.grid.x);
        uint highest = fine ? highestLevelRead(eyes) : 0u;
        for (uint level = 1u; level <= 3u; ++level)
            mipGroups[level - 1u] = level <= highest
                                        ? uvec4((columns + 7u) / 8u, pc.mipGroupsY, eyes, 0u)
                                        : uvec4(0u, 0u, 1u, 0u);
        return;
    }
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(cameraImageSize());
    if (p.x >= size.x || p.y >= size.y) return;
    uint eyes = clamp(vp.grid.z, 1u, 2u);
    uint eye = min(cameraEyeOf(uint(p.x)), eyes - 1u);
    VisualPolarMap m = vpMapOfEye(eye);
    vec2 local = vec2(p) + 0.5 - vec2(float(eye * cameraEyeSize().x), 0.0);
    vec2 rt = vpToVisualPolar(m, local);
    // Rows per screen pixel along phi: n / (2 pi r) with the continuous height n = H rho / rho_f
    // in the fovea (constant there: H / (2 pi r_f), no singularity at the gaze), H beyond; the
    // level brings it to <= 1 (P5 §3.4).
    float n = float(m.height) * min(rt.x / m.foveaFraction, 1.0);
    float rFovea = m.dMax * m.foveaDegrees / kVpMaxDegrees;
    float rowsPerPixel = rt.x < m.foveaFraction
                             ? float(m.height) / max(2.0 * kVpPi * rFovea, 1e-6)
                             : n / max(2.0 * kVpPi * length(local - m.gaze), 1e-6);
    float L = clamp(log2(max(rowsPerPixel, 1.0)), 0.0, float(max(pc.levels, 1u) - 1u));
    imageStore(lookup, p, vec4(rt, L, sigmaAt(m, local)));
    // unwarp.comp's full-screen dispatch samples level 0 only; where L > 0 the fine one blends
    // the levels, reading columns up to i0 + 1 (its bilinear(); one more for rounding).
    if (L > 0.0) {
        atomicMin(fineBox[eye].x, uint(p.x));
        atomicMin(fineBox[eye].y, uint(p.y));
        atomicMax(fineBox[eye].z, uint(p.x));
        atomicMax(fineBox[eye].w, uint(p.y));
        int i0 = int(floor(rt.x * float(m.width) - 0.5));
        atomicMax(fineColumn[eye], uint(clamp(i0 + 2, 0, int(m.width) - 1)));
    }
}
