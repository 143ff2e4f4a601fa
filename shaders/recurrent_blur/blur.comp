#version 460
// RecurrentBlur spatial filter, used three times (seed 004, the ReBLUR talk; specs §2):
//   mode 0 pre-blur   ("fixes outliers"): radiance -> preblurred, s' = 1/11, normal looseness 2
//   mode 1 blur       (the radius shrinks with the accumulated frame count N): color -> blurred
//   mode 2 post-blur  (radius x2, normal looseness 0.5): blurred -> history, the recurrent
//                     feedback of the next frame's temporal accumulation
// 8 rotated disk taps (talk: "8 samples"; our own Vogel-spiral disk, rotated per frame), weights
// = plane distance x normal x hit distance x Gaussian of the tap radius, centre weight 1.
// Output alpha: mode 0 and 2 the pixel's normalized hit distance h, mode 1 the count N.
// REBLUR_SPECULAR (signal = specular, seed 004 "Cooking specular denoiser"): the taps lie in the
// world-space kernel plane of the specular dominant direction (reblurKernelBasis, anisotropic at
// grazing angles) and are projected to the screen; the radius also scales with roughness and
// with the hit distance (lerp(K roughness, 1, f)); weights = plane distance x lobe-angle normal
// weight x roughness weight x hit distance x Gaussian.
#extension GL_GOOGLE_include_directive : require
#include "common/camera.glsl"
#include "common/color.glsl"
#include "common/hit_distance.glsl"
#include "recurrent_blur/reblur_common.glsl"
#include "recurrent_blur/reblur_specular.glsl"

#ifndef REBLUR_SPECULAR
#define REBLUR_SPECULAR 0
#endif

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D src;     // colour to filter (a = N in mode 1)
uniform sampler2D hitSrc;  // mode 0: raw hit distance (0 = miss); else normalized h (r32f)
uniform sampler2D normal;
uniform sampler2D position;
uniform sampler2D depth;
#if REBLUR_SPECULAR  // declared only where used: an unused sampler would sit at binding 0
uniform sampler2D roughness;  // GBuffer roughness_metallic (r = linear roughness)
#endif
layout(rgba32f) uniform writeonly image2D dst;
layout(r32f) uniform writeonly image2D radius;

layout(push_constant) uniform Params {
    ivec2 size;
    int eyeWidth;
    int eyes;
    float tanHalfFov;        // tan(fovY / 2) of the frame camera
    int mode;                // 0 pre, 1 blur, 2 post
    float maxRadius;         // px (mode 0: the pre-pass radius)
    float minRadius;         // px
    int linearScaling;       // 1: r ~ h s' (talk 1/(1+N)); 0: r ~ sqrt(h s') (NRD)
    float historyFixFrames;  // Nhf of the radius boost
    float planeDistance;     // plane-distance sensitivity, fraction of the frustum size
    float minHitWeight;      // floor of the hit-distance weight
    vec2 rotation;           // (cos, sin) of this frame's disk rotation
    int writeRadius;         // 1: store the radius used into `radius`
    int hitNormalized;       // mode 0: hitSrc holds the normalized h, not a distance
    float maxFrames;         // specular: N of a converged pixel (kernel skew, normal angle)
    float hitRadiusK;        // specular: K of lerp(K roughness, 1, f)
} pc;

// 8 points of a Vogel (golden-angle) spiral in the unit disk: r = sqrt((i + 0.5) / 8).
const vec2 kDisk[8] = vec2[8](vec2(0.250000, 0.000000), vec2(-0.319290, 0.292496),
                              vec2(0.048872, -0.556877), vec2(0.402444, 0.524918),
                              vec2(-0.738535, -0.130636), vec2(0.699605, -0.445031),
                              vec2(-0.234004, 0.870484), vec2(-0.446271, -0.859268));

// A normalized input of -1 (PathTrace.*_hit: no ray of that lobe at this pixel) has no data; the
// weights read it as far (1), the specular pre-blur rebuilds it from its taps (main).
bool hitKnown(ivec2 q) {
    return pc.mode != 0 || pc.hitNormalized == 0 || texelFetch(hitSrc, q, 0).r >= 0.0;
}

float hitOf(ivec2 q) {
    float v = texelFetch(hitSrc, q, 0).r;
    if (pc.mode != 0 || pc.hitNormalized != 0)
        return isnan(v) || isinf(v) || v < 0.0 ? 1.0 : clamp(v, 0.0, 1.0);
    float z = texelFetch(depth, q, 0).r;
    if (!(z > 0.0)) return 1.0;
#if REBLUR_SPECULAR
    // A raw distance: normalized as PathTrace.specular_hit would be (hit_distance.glsl).
    float rq = clamp(sanitize(texelFetch(roughness, q, 0)).r, 0.0, 1.0);
    return normalizeHitDistance(v, hitDistanceScale(pc.tanHalfFov, z, rq));
#else
    return normalizedHit(v, frustumSize(pc.tanHalfFov, z));
#endif
}

vec3 unitNormal(vec4 n) {
    float l = length(n.xyz);
    return l > 1e-8 && !isnan(l) && !isinf(l) ? n.xyz / l : vec3(0.0, 0.0, 1.0);
}

#if REBLUR_SPECULAR
// Pre-blur: the normalized hit distance of a pixel, rebuilt from 8 neighbours two pixels away (a
// 5x5 footprint at a third of the fetches of all 24) where the pixel traced no specular ray (-1; at 1 spp most pixels trace one lobe), so the temporal
// stage's virtual motion has a distance everywhere (NRD does the same,
// REBLUR_HIT_DIST_RECONSTRUCTION). Taps: same plane (plane distance), normals within ~25 deg,
// similar roughness. 1 (far) when no neighbour has one.
float reconstructedHit(ivec2 p, vec3 x, vec3 nrm, float r0, float z, ivec2 lo, ivec2 hi) {
    if (hitKnown(p)) return hitOf(p);
    float frustum = frustumSize(pc.tanHalfFov, z);  // > 0: the caller checks z > 0
    float sum = 0.0, wsum = 0.0;
    for (int j = -2; j <= 2; j += 2)
        for (int i = -2; i <= 2; i += 2) {
            if (i == 0 && j == 0) continue;
            ivec2 q = clamp(p + ivec2(i, j), lo, hi);
            if (!hitKnown(q) || !(texelFetch(depth, q, 0).r > 0.0)) continue;
            vec3 xq = texelFetch(position, q, 0).xyz;
            float w = reblurWeight(dot(nrm, xq - x) / (pc.planeDistance * frustum)) *
                      clamp((dot(nrm, unitNormal(texelFetch(normal, q, 0))) - 0.9) / 0.1, 0.0,
                            1.0) *
                      reblurRoughnessWeight(r0, clamp(texelFetch(roughness, q, 0).r, 0.0, 1.0));
            if (!(w > 0.0)) continue;
            sum += w * hitOf(q);
            wsum += w;
        }
    return wsum > 0.0 ? sum / wsum : 1.0;  // wsum > 0 checked
}
#endif

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    ivec2 lo, hi;
    eyeBounds(p, pc.size, pc.eyeWidth, pc.eyes, lo, hi);

    // Every output pixel is written, sky included (specs §2: NRD #88), and NaN/Inf inputs become
    // 0 before anything reads them (the recurrence would make one NaN permanent).
    vec4 c = sanitize(texelFetch(src, p, 0));
    float z = texelFetch(depth, p, 0).r;
    float hp = hitOf(p);
    float n = pc.mode == 1 ? max(c.a, 0.0) : 0.0;
    float outAlpha = pc.mode == 1 ? c.a : hp;

    vec3 x = texelFetch(position, p, 0).xyz;
    vec3 nrm = unitNormal(texelFetch(normal, p, 0));
    uint eye = uint(min(p.x / pc.eyeWidth, pc.eyes - 1));
    vec3 toEye = camera_info.eyes[eye].position.xyz - x;  // view vector for NoV
    float nov = length(toEye) > 1e-12 ? abs(dot(nrm, normalize(toEye))) : 1.0;

    // s': the blur's accumulation-dependent scale (specs §2 "Radius"); the pre-pass uses 1/11.
    float s = pc.mode == 0 ? 1.0 / 11.0 : radiusScale(n, pc.historyFixFrames, nov);
    float fs = pc.mode == 0 ? 2.0 : (pc.mode == 1 ? 1.0 : 0.5);  // normal-weight looseness
    float scale = pc.linearScaling != 0 ? hp * (pc.mode == 0 ? 1.0 : s)
                                        : sqrt(hp * (pc.mode == 0 ? 1.0 : s));  // h s' >= 0
    float r = max(pc.minRadius, pc.maxRadius * scale) * (pc.mode == 2 ? 2.0 : 1.0);
#if REBLUR_SPECULAR
    float r0 = clamp(sanitize(texelFetch(roughness, p, 0)).r, 0.0, 1.0);
    float viewDistance = length(toEye);
    float hitDist = z > 0.0 ? denormalizeHitDistance(
                                  hp, hitDistanceScale(pc.tanHalfFov, z, r0))
                            : 0.0;
    r *= reblurSpecularRadiusScale(r0) *
         reblurHitDistanceRadiusFactor(hitDist, viewDistance, r0, pc.hitRadiusK);
#endif
    if (pc.writeRadius != 0) imageStore(radius, p, vec4(z > 0.0 ? r : 0.0));

#if REBLUR_SPECULAR
    if (pc.mode == 0 && z > 0.0) outAlpha = reconstructedHit(p, x, nrm, r0, z, lo, hi);
#endif
    if (!(z > 0.0) || r < 0.5) {  // sky, or a radius below half a pixel: the centre alone
        imageStore(dst, p, vec4(c.rgb, outAlpha));
        return;
    }

    float frustum = frustumSize(pc.tanHalfFov, z);  // > 0: z > 0
    // Normal lobe: tan of the half angle of a roughness-1 lobe shrinking with s' (specs §2,
    // theta0 = 60 deg at N = 0 ... 11.6 deg at N = 30). P in [0.017, 0.75]: 1 - P > 0.
    float prob = 0.75 * mix(0.0225, 1.0, s);
    float theta0 = max(atan(sqrt(prob / (1.0 - prob))), 1.5 / 255.0);
    float hitNorm = mix(5e-4, 1.0, s);  // > 0
    float hitFloor = pc.minHitWeight * fs * sqrt(s);

    vec3 sum = c.rgb;
    float wsum = 1.0;
#if REBLUR_SPECULAR
    // World-space kernel: r pixels at depth z are r * frustum / rows world units.
    vec3 kernelT, kernelB;
    float normalizedFrames = pc.maxFrames > 0.0 ? clamp(n / pc.maxFrames, 0.0, 1.0) : 1.0;
    vec3 toEyeDir = viewDistance > 0.0 ? toEye / viewDistance : nrm;  // viewDistance > 0
    reblurKernelBasis(nrm, toEyeDir, r0, r * frustum / float(pc.size.y), normalizedFrames,
                      kernelT, kernelB);
    // The talk's CloseToZeroIfAccumulationGoesWell: the lobe angle narrows with s'.
    float shrink = fs * mix(0.25, 1.0, s);
    CameraEye cam = camera_info.eyes[eye];
#endif
    for (int i = 0; i < 8; ++i) {
        vec2 d = kDisk[i];
        vec2 dr = vec2(d.x * pc.rotation.x - d.y * pc.rotation.y,
                       d.x * pc.rotation.y + d.y * pc.rotation.x);
#if REBLUR_SPECULAR
        vec4 clip = cam.viewProj * vec4(x + kernelT * dr.x + kernelB * dr.y, 1.0);
        if (!(clip.w > 1e-6)) continue;  // behind the eye; guards the division
        vec2 ndc = clip.xy / clip.w;
        vec2 tap = vec2((ndc.x * 0.5 + 0.5) * float(pc.eyeWidth) + cam.position.w,
                        (0.5 - ndc.y * 0.5) * float(pc.size.y));
        if (any(isnan(tap)) || any(isinf(tap))) continue;
        ivec2 q = clamp(ivec2(floor(clamp(tap, vec2(-1e6), vec2(1e6)))), lo, hi);
#else
        vec2 o = dr * r;
        ivec2 q = clamp(ivec2(floor(vec2(p) + 0.5 + o)), lo, hi);  // never across the eye seam
#endif
        float zq = texelFetch(depth, q, 0).r;
        if (!(zq > 0.0)) continue;  // sky tap
        vec3 xq = texelFetch(position, q, 0).xyz;
        vec3 nq = unitNormal(texelFetch(normal, q, 0));
        float wg = reblurWeight(dot(nrm, xq - x) / (pc.planeDistance * frustum));
#if REBLUR_SPECULAR
        float rq = clamp(sanitize(texelFetch(roughness, q, 0)).r, 0.0, 1.0);
        float wn = reblurSpecularNormalWeight(nrm, nq, r0, shrink) * reblurRoughnessWeight(r0, rq);
#else
        float angle = acos(clamp(dot(nrm, nq), -1.0, 1.0));
        float wn = reblurWeight(angle / (theta0 * fs));  // theta0 >= 1.5/255
#endif
        float wh = mix(hitFloor, 1.0, exp(-3.0 * abs(hitOf(q) - hp) / hitNorm));
        float w = wg * wn * wh * exp(-0.66 * dot(d, d));
        if (!(w > 0.0)) continue;  // a weight-0 tap adds nothing, even a NaN one
        sum += w * sanitize(texelFetch(src, q, 0)).rgb;
        wsum += w;
    }
    imageStore(dst, p, sanitize(vec4(sum / wsum, outAlpha)));  // wsum >= 1
}
