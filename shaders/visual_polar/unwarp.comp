#version 460
// Unwarp step 2 (seed 003 P5 §3.4): backward mapping. Every screen pixel finds its (rho, phi)
// in its eye's Visual-Polar image and samples it: bilinear in rho between two columns (clamped
// to the edge), in each column bilinear in phi at that column's own height, wrapped (hides the
// phi seam); trilinear across the phi-only mips where one pixel covers several phi rows (the
// fovea). The gaze pixel maps to rho ~ 0, t = 0: finite, never a division by zero.
// P5 §3.4 precomputes the sampling positions: the per-pixel (rho, t), mip level and blur sigma
// live in the persistent `lookup` image and are recomputed only when the mapping key (the `vp`
// block, the field of view, the level count and the blur profile) differs from the one stored
// in `lookup_key` by the last rebuild (mode 1 stores it after the frame's mapping dispatch).
#extension GL_GOOGLE_include_directive : require

#include "../common/camera.glsl"
#define VISUAL_POLAR_PARAMS
#include "../common/visual_polar.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;
layout(rgba32f) uniform readonly image2D mip1;
layout(rgba32f) uniform readonly image2D mip2;
layout(rgba32f) uniform readonly image2D mip3;
layout(rgba32f) uniform writeonly image2D unwarped;
layout(rgba32f) uniform writeonly image2D result;
// Per pixel: x rho, y t, z mip level L, w the blur's sigma (P5 §3.5); persistent.
layout(rgba32f) uniform image2D lookup;
layout(std430) buffer LookupKey { uvec4 key[5]; } lookup_key;

layout(push_constant) uniform Params {
    uint levels;        // 1..4
    uint toResult;      // 1: write `result` (no blur follows), 0: `unwarped` and `sigma`
    float sigmaMax;     // blur sigma (pixels) at blurDegrees for this height
    float blurDegrees;  // >= 1
    uint useCache;      // 0: recompute the lookup every frame (benchmarks, tests)
    uint mode;          // 0: map, 1: store the key of this frame (one thread)
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


vec4 loadLevel(uint level, ivec2 p) {
    if (level == 0u) return texelFetch(color, p, 0);
    if (level == 1u) return imageLoad(mip1, p);
    if (level == 2u) return imageLoad(mip2, p);
    return imageLoad(mip3, p);
}

// One column at its own phi height for this level; t wraps.
vec4 columnSample(VisualPolarMap m, uint eye, uint column, float t, uint level) {
    uint n = vpRowsAtLevel(m, column, level);  // >= 1
    float y = fract(t) * float(n) - 0.5;
    float j0f = floor(y);
    float fy = y - j0f;
    int j0 = int(j0f);
    int a = (j0 % int(n) + int(n)) % int(n);
    int b = (a + 1) % int(n);
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

void main() {
    if (pc.mode == 1u) {
        if (gl_GlobalInvocationID.xy == uvec2(0u))
            for (int k = 0; k < 5; ++k) lookup_key.key[k] = mappingKey(k);
        return;
    }
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(cameraImageSize());
    if (p.x >= size.x || p.y >= size.y) return;
    uint eyes = clamp(vp.grid.z, 1u, 2u);
    uint eye = min(cameraEyeOf(uint(p.x)), eyes - 1u);
    VisualPolarMap m = vpMapOfEye(eye);
    bool stale = pc.useCache == 0u;
    for (int k = 0; k < 5; ++k) stale = stale || any(notEqual(lookup_key.key[k], mappingKey(k)));
    vec4 lk;
    if (stale) {
        vec2 local = vec2(p) + 0.5 - vec2(float(eye * cameraEyeSize().x), 0.0);
        vec2 rt = vpToVisualPolar(m, local);
        // Rows per screen pixel along phi: n / (2 pi r) with the continuous height n = H rho /
        // rho_f in the fovea (constant there: H / (2 pi r_f), no singularity at the gaze), H
        // beyond; the level brings it to <= 1 (P5 §3.4).
        float n = float(m.height) * min(rt.x / m.foveaFraction, 1.0);
        float rFovea = m.dMax * m.foveaDegrees / kVpMaxDegrees;
        float rowsPerPixel = rt.x < m.foveaFraction
                                 ? float(m.height) / max(2.0 * kVpPi * rFovea, 1e-6)
                                 : n / max(2.0 * kVpPi * length(local - m.gaze), 1e-6);
        float L = clamp(log2(max(rowsPerPixel, 1.0)), 0.0, float(max(pc.levels, 1u) - 1u));
        lk = vec4(rt, L, sigmaAt(m, local));
        imageStore(lookup, p, lk);
    } else {
        lk = imageLoad(lookup, p);
    }
    vec2 rt = lk.xy;
    float L = lk.z;
    uint l0 = uint(floor(L));
    uint l1 = min(l0 + 1u, max(pc.levels, 1u) - 1u);
    vec4 c = bilinear(m, eye, rt, l0);
    // Only where level l1 has a weight: most of the periphery maps at L = 0 exactly (at most one
    // phi row per pixel), so it skips half the fetches.
    float fl = L - float(l0);
    if (l1 != l0 && fl > 0.0) c = mix(c, bilinear(m, eye, rt, l1), fl);
    // NaN/Inf in the VP image never reach the screen.
    if (any(isnan(c)) || any(isinf(c))) c = vec4(0.0);
    if (pc.toResult != 0u) imageStore(result, p, c);
    else imageStore(unwarped, p, c);
}
