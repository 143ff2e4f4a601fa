#version 460
// ATrousNH: one level of the non-homogeneous edge-avoiding à-trous filter (seed 000 §3.4,
// Eq. 2, Algorithm 1; Dammertz et al. 2010). The pass dispatches this shader once per level of
// its schedule, ping-ponging between two state images (rgb colour, a = valid 0/1): `ping` and
// `denoised`, so that the last level lands in `denoised`.
//  - Pixels of layers not in `activeLayers` are copied unchanged (Algorithm 1: "each iteration
//    in a layer reconstructs only the area corresponding to that layer"); neighbours are read
//    from any layer.
//  - b(i, j) of Eq. 2 is the neighbour's validity: an unsampled pixel never contributes.
//  - Taps outside the image or in the other eye are skipped (§3.4: "neighbor pixels could be out
//    of screen"; stereo images are side by side, §3.3).
//  - No holes: a pixel without a value takes the mean of the valid taps and becomes valid (a
//    source for later levels); hole-fill levels (fillOnly) update only such pixels.
#extension GL_GOOGLE_include_directive : require
#include "common/camera.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;
uniform sampler2D normal;
uniform sampler2D position;
layout(r32ui) uniform readonly uimage2D mask;
layout(rgba32f) uniform image2D ping;
layout(rgba32f) uniform image2D denoised;  // also the source of even fill levels (src 3)
// Hole counter of the GPU-driven fill levels (fill_args.comp turns it into group counts).
layout(std430) buffer atrous_fill {
    uvec4 fillArgs;
    uvec4 copyArgs;
    uint holes;
    uint executed;
};
// Tile lists (tile_lists.comp): with tileKey > 0 a workgroup handles the 8x8 tile listed at its
// index in list tileKey, so a level runs only on the tiles holding its layers.
layout(std430) readonly buffer atrous_tiles {
    uvec4 tileArgs[8];  // per key: indirect (x, y, 1) + tile count in .w
    uint tileIds[];     // key k's tiles at [k * tileStride, ...), packed x | y << 16
};

layout(push_constant) uniform Params {
    ivec2 size;
    int eyeWidth;      // >= 1
    int eyes;          // 1 or 2
    int layerCount;    // 1..3
    int useMask;
    int src;           // 0 = input color (+ mask), 1 = ping, 3 = denoised
    int dst;           // 0 = denoised, 1 = ping
    int activeLayers;  // bit l: layer l is updated
    int stepWidth;     // 2^i
    int fillOnly;      // 1: only pixels without a value are updated
    int countHoles;    // 1: count the pixels still without a value into atrous_fill.holes
    float invSigmaColor2;     // 1 / sigma^2; 0 = term off
    float invSigmaNormal2;
    float invSigmaPosition2;
    int positionRelative;  // 1: position distances in units of p's distance to its eye
    int positionPlane;     // 1: tangent-plane distance |n_p . (x_q - x_p)|; 0: |x_q - x_p|
    float invSigmaTangent2;  // plane term: 1 / sigmaTangent^2 on the distance along the plane
    // Tile-restricted dispatch (appended after any other field):
    int tileKey;     // 0: full screen (one invocation per pixel); k > 0: tiles of list k
    int tileStride;  // capacity of one tile list
    int alsoDst;     // -1, or a second destination of the pixels copied unchanged (0 / 1)
} pc;

// Mask word (FoveationMask): bit 0 sampled (B of Eq. 2), bits 1-2 layer id, bits 16-31 spp.
const uint kSampledBit = 1u;
const float kB3[5] = float[5](1.0 / 16.0, 1.0 / 4.0, 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);

bool finite4(vec4 v) { return !any(isnan(v)) && !any(isinf(v)); }

// State of pixel q: rgb and validity. From the input, invalid pixels read as 0 so that their
// (possibly huge or NaN) colour is never even copied.
vec4 loadState(ivec2 q) {
    if (pc.src == 1) return imageLoad(ping, q);
    if (pc.src == 3) return imageLoad(denoised, q);
    vec4 c = texelFetch(color, q, 0);
    bool ok = c.a > 0.0 && finite4(c);
    if (pc.useMask != 0) ok = ok && (imageLoad(mask, q).r & kSampledBit) != 0u;
    return ok ? vec4(c.rgb, 1.0) : vec4(0.0);
}

void storeTo(int image, ivec2 p, vec4 s) {
    if (image == 1) imageStore(ping, p, s);
    else imageStore(denoised, p, s);
}

void storeState(ivec2 p, vec4 s) {
    if (pc.countHoles != 0 && s.a <= 0.5) atomicAdd(holes, 1u);
    storeTo(pc.dst, p, s);
}

int layerOf(ivec2 p) {
    if (pc.useMask == 0 || pc.layerCount <= 1) return 0;
    return int(min((imageLoad(mask, p).r >> 1) & 3u, uint(pc.layerCount - 1)));
}

// exp(-exponent) in [0, 1]; a NaN (non-finite G-buffer) counts as no similarity.
float edgeWeight(float exponent) {
    float w = exp(-exponent);
    return isnan(w) ? 0.0 : w;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (pc.tileKey > 0) {
        // Workgroups beyond the list's count fill the last row of a 2D indirect grid.
        uint index = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
        if (index >= tileArgs[pc.tileKey].w) return;
        uint tile = tileIds[uint(pc.tileKey * pc.tileStride) + index];
        p = ivec2(tile & 0xffffu, tile >> 16) * 8 + ivec2(gl_LocalInvocationID.xy);
    }
    if (any(greaterThanEqual(p, pc.size))) return;
    vec4 centre = loadState(p);
    bool centreValid = centre.a > 0.5;
    bool updated = pc.fillOnly != 0 ? !centreValid : ((pc.activeLayers >> layerOf(p)) & 1) != 0;
    if (!updated) {
        storeState(p, centre);
        // Tile path, first level: an unchanged pixel is valid in both state images, so levels
        // that skip its tile need not copy it (ATrousNHPass.cpp, "tile lists").
        if (pc.alsoDst >= 0) storeTo(pc.alsoDst, p, centre);
        return;
    }
    int eye = min(p.x / pc.eyeWidth, pc.eyes - 1);  // eyeWidth >= 1 (pass clamps)
    int x0 = eye * pc.eyeWidth;
    int x1 = eye == pc.eyes - 1 ? pc.size.x : x0 + pc.eyeWidth;
    vec3 np = texelFetch(normal, p, 0).xyz;
    vec4 xpFull = texelFetch(position, p, 0);
    vec3 xp = xpFull.xyz;
    float xpHit = xpFull.w;
    // The normal term shrinks with the step (Dammertz's reference code); stepWidth >= 1.
    float invN2 = pc.invSigmaNormal2 / float(pc.stepWidth * pc.stepWidth);
    float invX2 = pc.invSigmaPosition2;
    float invT2 = pc.invSigmaTangent2;
    if (pc.positionRelative != 0) {
        // Scale-invariant position term: |x_p - x_q| / |x_p - eye|. The floor keeps the division
        // finite for a point at the eye (then every other position is far, weight ~0).
        uint cameraEye = min(uint(eye), max(cameraEyeCount(), 1u) - 1u);
        vec3 toEye = xp - camera_info.eyes[cameraEye].position.xyz;
        invX2 /= max(dot(toEye, toEye), 1e-30);
        invT2 /= max(dot(toEye, toEye), 1e-30);
    }

    // The centre tap has every distance 0, so weight 1 (a NaN G-buffer at p, which would
    // make it 0, makes every other tap 0 as well: the result is the centre either way).
    const float kCentreH = kB3[2] * kB3[2];
    float cum = centreValid ? kCentreH : 0.0, plainCum = cum;
    vec3 sum = centreValid ? centre.rgb * kCentreH : vec3(0.0), plainSum = sum;
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            if (dx == 0 && dy == 0) continue;  // the centre, above
            ivec2 q = p + pc.stepWidth * ivec2(dx, dy);
            if (q.x < x0 || q.x >= x1 || q.y < 0 || q.y >= pc.size.y) continue;
            vec4 s = loadState(q);
            if (s.a <= 0.5) continue;  // b(i, j) = 0: never sampled, not filled yet
            float h = kB3[dx + 2] * kB3[dy + 2];
            // The edge-stopping terms multiply (Dammertz Eq. 6 and its normal and position
            // terms), so their exponents add: one exp per tap instead of one per term. Every
            // term is >= 0, so the sum is >= 0 or +inf (weight 0); a NaN from a non-finite
            // G-buffer makes the weight 0 below, as each term's own NaN did.
            float e = 0.0;
            // Without a centre value there is no colour to compare with: geometry only.
            if (centreValid && pc.invSigmaColor2 > 0.0) {
                vec3 d = centre.rgb - s.rgb;
                e += dot(d, d) * pc.invSigmaColor2;
            }
            if (pc.invSigmaNormal2 > 0.0) {
                vec3 d = np - texelFetch(normal, q, 0).xyz;
                e += dot(d, d) * invN2;
            }
            if (pc.invSigmaPosition2 > 0.0) {
                vec4 xq = texelFetch(position, q, 0);
                vec3 d = xq.xyz - xp;
                // Plane term (seed 004 "plane distance", ReBLUR's geometry weight): a tap on
                // p's tangent plane has distance 0 however far along the surface it lies, so
                // the large steps still average a flat wall; a tap in front of or behind the
                // plane is rejected. Hit and miss never mix (w = 1 hit, GBuffer).
                float d2 = dot(d, d);
                if (pc.positionPlane != 0) {
                    float t = dot(np, d);
                    // Along the plane a separate, looser sigma bounds the reach (0 = unbounded).
                    e += max(d2 - t * t, 0.0) * invT2;
                    d2 = xq.w == xpHit ? t * t : 1e30;
                }
                e += d2 * invX2;
            }
            float w = edgeWeight(e);
            sum += s.rgb * (w * h);
            cum += w * h;
            plainSum += s.rgb * h;
            plainCum += h;
        }
    }
    vec4 result;
    if (cum > 1e-30) result = vec4(sum / cum, 1.0);  // guarded division
    else if (centreValid) result = centre;           // unreachable: the centre has w = 1
    else if (plainCum > 0.0) result = vec4(plainSum / plainCum, 1.0);  // all weights underflowed
    else result = centre;  // no valid tap: stays without a value (a later level fills it)
    storeState(p, result);
}
