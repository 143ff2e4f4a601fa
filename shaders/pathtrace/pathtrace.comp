#version 460
// PathTrace: the real-time "1 spp" ray configuration of Koskela et al. (seed 003, P2 §3.1 and P5
// §3.1) as used by Peres et al. (seed 000 §3.3, §4.1): per sample one primary hit (the GBuffer's
// `visibility` or an own jittered camera ray), next-event estimation (one shadow ray to a random
// point on a random light), then `maxBounces` (default 1) BRDF-sampled indirect rays, each
// followed by next-event estimation at its hit. Emission found by an indirect ray is combined
// with next-event estimation by multiple importance sampling (Veach & Guibas 1995, Veach 1997
// §9.2, power heuristic beta = 2); so is the environment a BRDF ray finds when it escapes
// (pbrt-v3 §14.2.4's importance-sampled infinite light). At the last vertex (PATHTRACE_LAST_MIS,
// parameter lastBounceMis) one more BRDF-sampled ray looks for an emitter only and is
// MIS-weighted against that vertex's shadow ray, which bounds the estimate where the light
// sample's area-to-solid-angle factor d^2 / (A cos) explodes (points next to an emitter);
// without it the last shadow ray takes full weight (docs/passes/PathTrace.md "Emission and MIS").
//
// Random numbers: a stateless hash of (pixel, frame, sample, bounce, dimension, graph seed)
// (shaders/common/random.glsl), so reruns are bit-identical on one driver.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8) in;

#include "common/bvh.glsl"
#include "common/camera.glsl"
#include "common/color.glsl"
#include "common/hit_distance.glsl"
#include "common/random.glsl"
#include "common/sample_layout.glsl"
#include "common/scene_sample.glsl"
#include "common/specular_albedo.glsl"
#include "pathtrace/brdf.glsl"

layout(rgba32ui) uniform readonly uimage2D visibility;
uniform sampler2D albedo;
layout(rgba32f) uniform writeonly image2D radiance;
layout(rgba32f) uniform writeonly image2D demodulated;
layout(r32f) uniform writeonly image2D hit_distance;
layout(rgba16f) uniform writeonly image2D direct;
layout(rgba16f) uniform writeonly image2D indirect;
// The signals split by lobe at the primary vertex (issue 26, docs/passes/PathTrace.md "Diffuse and
// specular signals"): rgb demodulated, a = samples; *_hit = normalized hit distance of the lobe's
// own first rays (hit_distance.glsl), -1 where no ray of that lobe was traced.
layout(rgba32f) uniform writeonly image2D diffuse;
layout(rgba32f) uniform writeonly image2D specular;
layout(rgba16f) uniform writeonly image2D diffuse_albedo;
layout(rgba16f) uniform writeonly image2D specular_albedo;
layout(r16f) uniform writeonly image2D diffuse_hit;
layout(r16f) uniform writeonly image2D specular_hit;

#ifndef PATHTRACE_COUNT_RAYS
#define PATHTRACE_COUNT_RAYS 0
#endif
#ifndef PATHTRACE_LAST_MIS
#define PATHTRACE_LAST_MIS 0
#endif
#ifndef PATHTRACE_EMITTER_SAMPLING
#define PATHTRACE_EMITTER_SAMPLING 0
#endif
// Parameter emitterSampling: how light reaching a vertex from an area emitter is estimated.
// 0 mis: shadow ray and BRDF ray, power heuristic (the default, Veach 1997 §9.2);
// 1 light: shadow rays only (a BRDF ray that finds an emitter adds nothing);
// 2 brdf: BRDF rays only (no shadow rays to area lights; the last vertex traces its BRDF ray).
// 1 and 2 are the two single-strategy estimators MIS combines: each is unbiased on its own, so
// all three must converge to the same image (tests/graph/PathTraceMisTests.cpp).
// Punctual lights are reached by shadow rays only and keep full weight in every mode.
#if PATHTRACE_EMITTER_SAMPLING == 2
#define PATHTRACE_LAST_RAY 1
#elif PATHTRACE_EMITTER_SAMPLING == 1
#define PATHTRACE_LAST_RAY 0
#else
#define PATHTRACE_LAST_RAY PATHTRACE_LAST_MIS
#endif
#if PATHTRACE_COUNT_RAYS
// Benchmark builds (parameter countRays): rays traced, by kind: 0 primary (own camera rays),
// 1 shadow rays from the primary hit, 2 indirect rays, 3 shadow rays from indirect hits, 4 the
// last vertex's emitter-seeking BRDF rays (lastBounceMis).
const int kRayKinds = 5;
layout(std430) buffer PathTraceRays {
    uint counts[kRayKinds];
} pathtrace_rays;
uint gRays[kRayKinds] = uint[kRayKinds](0u, 0u, 0u, 0u, 0u);
#define COUNT_RAY(kind) (gRays[kind] += 1u)
#else
#define COUNT_RAY(kind)
#endif

layout(push_constant) uniform Params {
    ivec2 size;
    uint seedLo;  // graph seed (FrameInfo::seed), low and high 32 bits
    uint seedHi;
    int spp;            // samples per pixel without a layout
    int maxBounces;     // indirect rays per path
    int useVisibility;  // 1: primary hits come from `visibility`
    int useAlbedo;      // 1: demodulate with the `albedo` input
    int useLayout;      // 1: trace only the pixels of the sample layout
    float clampIndirect;  // > 0: max channel of one indirect contribution (biased); 0 = off
} pc;

const float kAlbedoEpsilon = 1e-3;  // CONTRACT: albedo' = albedo > 1e-3 ? albedo : 1
const float kShadowShorten = 0.9999;  // shadow rays stop just before the light point
const float kInfinity = 1e30;
const float kHalfMax = 65504.0;
const uint kVisTraced = 1u;
const uint kVisHit = 2u;
const uint kVisClipped = 4u;  // GBuffer on a Visual-Polar grid: a texel that is never traced

// Dimensions per path vertex: 4 for the light sample, 3 for the BRDF sample; 2 for the pixel.
const uint kDimPixel = 0u;
const uint kDimLight = 2u;
const uint kDimBrdf = 6u;
const uint kDimsPerVertex = 9u;

uint gSampleSeed;

float rand(uint vertex, uint dim) {
    return uintToUnitFloat(hashCombine(gSampleSeed, vertex * kDimsPerVertex + dim));
}

// Seed of the alpha test's BLEND decisions (bvh.glsl) for the shadow ray (kind 0) or the BRDF /
// camera ray (kind 1) leaving `vertex` (0 = the camera): an own hash stream, far from rand()'s
// small indices, so adding it changed no other random number. Unused (compiled out) when the
// scene has no alpha-tested material.
const uint kAlphaSeedBase = 0xA1FA0000u;
uint alphaSeed(uint vertex, uint kind) {
    return hashCombine(gSampleSeed, kAlphaSeedBase + 2u * vertex + kind);
}

#ifndef PATHTRACE_STRATIFY_LIGHT
#define PATHTRACE_STRATIFY_LIGHT 0
#endif
#if PATHTRACE_STRATIFY_LIGHT
// Parameter stratifyLight: the light samples of the primary vertex (light column, point on the
// triangle) of one pixel's samples form a randomly shifted 3-D R-sequence (Roberts 2018,
// additive recurrence with the generalized golden ratio phi_3, x^4 = x + 1), i.e. a
// Cranley-Patterson rotation of a low-discrepancy point set: each point is uniform (the shift
// is), so the estimate stays unbiased, and the pixel's samples cover the light evenly instead of
// clumping. With GBuffer primaries all samples of a pixel shade the same point, so this is
// stratified direct lighting at that point. The alias coin (u.y) stays independent.
uint gPixelSeed;
uint gSampleIndex;
const vec3 kR3 = vec3(0.8191725134, 0.6710436067, 0.5497004779);  // 1/phi_3, 1/phi_3^2, ^3
vec4 primaryLightSample() {
    vec3 shift = vec3(uintToUnitFloat(hashCombine(gPixelSeed, 0xA511u)),
                      uintToUnitFloat(hashCombine(gPixelSeed, 0xA512u)),
                      uintToUnitFloat(hashCombine(gPixelSeed, 0xA513u)));
    vec3 u = fract(shift + float(gSampleIndex) * kR3);
    // GLSL does not promise fract < 1 exactly: clamp to the largest float below 1, as
    // uintToUnitFloat's range [0, 1).
    u = min(u, vec3(0.99999994));
    return vec4(u.x, rand(1u, kDimLight + 1u), u.y, u.z);
}
#endif

float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

vec3 finiteOrZero(vec3 v) { return sanitize(vec4(v, 0.0)).rgb; }

// Power heuristic (Veach), beta = 2; a + b > 0 whenever a > 0.
float powerHeuristic(float a, float b) {
    float a2 = a * a;
    float d = a2 + b * b;
    return d > 0.0 ? a2 / d : 0.0;
}

// Weight of a shadow-ray sample of an area light; `brdfRayFollows`: this vertex also traces a
// BRDF ray that could find the same emitter.
float lightSampleWeight(float lightPdf, float brdfPdfValue, bool brdfRayFollows) {
#if PATHTRACE_EMITTER_SAMPLING == 1
    return 1.0;
#elif PATHTRACE_EMITTER_SAMPLING == 2
    return 0.0;
#else
    return brdfRayFollows ? powerHeuristic(lightPdf, brdfPdfValue) : 1.0;
#endif
}

// Weight of emission found by a BRDF-sampled ray (solid-angle pdfs of both strategies).
float brdfHitWeight(float brdfPdfValue, float lightPdf) {
#if PATHTRACE_EMITTER_SAMPLING == 1
    return 0.0;
#elif PATHTRACE_EMITTER_SAMPLING == 2
    return 1.0;
#else
    return powerHeuristic(brdfPdfValue, lightPdf);
#endif
}

// Light a BRDF-sampled ray finds when it leaves the scene: the environment, weighted against its
// next-event sample (sceneEnvironmentPdf includes the environment's selection probability).
vec3 escapedRadiance(vec3 wi, float brdfPdfValue) {
    if (!sceneHasEnvironment()) return vec3(0.0);
    vec3 le = sceneEnvironmentRadiance(wi);
    if (maxComponent(le) <= 0.0) return vec3(0.0);
    return le * brdfHitWeight(brdfPdfValue, sceneEnvironmentPdf(wi));
}

vec3 clampContribution(vec3 c) {
    if (pc.clampIndirect <= 0.0) return c;
    float m = maxComponent(c);
    return m > pc.clampIndirect ? c * (pc.clampIndirect / m) : c;  // m > clamp > 0
}

// The surface as the path sees it: normals turned to the side the ray arrived from.
struct Vertex {
    vec3 position;
    vec3 ng;  // geometric normal on the side of wo
    vec3 ns;  // shading normal, same side as ng and as wo (else ng)
    vec3 nSmooth;  // interpolated normal before the normal texture, on the side of ng
    vec3 wo;  // towards the previous vertex
    BrdfInput brdf;
    vec3 emitted;  // radiance leaving towards wo
};

Vertex makeVertex(uint triangle, vec2 bary, vec3 rayDir) {
    SceneSurface s = sceneSurface(triangle, bary);
    vec3 smoothNormal = s.normal;
    sceneApplyNormalMap(s);  // glTF §3.9.3 normal texture; ng stays for offsets and leaks
    SceneMaterialSample m = sceneSurfaceMaterial(s);
    bool front = dot(s.geometricNormal, rayDir) < 0.0;
    Vertex v;
    v.position = s.position;
    v.wo = -rayDir;
    v.ng = front ? s.geometricNormal : -s.geometricNormal;
    vec3 ns = dot(s.normal, v.ng) < 0.0 ? -s.normal : s.normal;
    // Interpolated normals can face away from the viewer at silhouettes: fall back.
    v.ns = dot(ns, v.wo) > 0.0 ? ns : v.ng;
    v.nSmooth = dot(smoothNormal, v.ng) < 0.0 ? -smoothNormal : smoothNormal;
    v.brdf.baseColor = m.baseColor;
    v.brdf.metallic = m.metallic;
    v.brdf.roughness = m.roughness;
    v.emitted = sceneEmission(s.material, s.uv, front);
    return v;
}

struct PathResult {
    vec3 direct;     // primary emission + light reaching the eye after one reflection
    vec3 indirect;   // after two or more reflections
    vec3 emission;   // primary emission alone (for demodulation)
    vec3 albedo;     // own first-hit base colour (0 on a miss)
    float hitT;      // first indirect ray's hit distance, 0 = no hit
    // Split at the primary vertex by lobe (emission excluded): diffuse + specular = direct +
    // indirect - emission before clamping.
    vec3 diffuse, specular;
    vec3 diffuseAlbedo;   // (1 - metallic) baseColor (Lambert: baseColor)
    vec3 specularAlbedo;  // pre-integrated E(F0, roughness, NoV) (0 for Lambert)
    float roughness;      // primary vertex (1 for Lambert)
    float viewZ;          // primary vertex's view depth
    int hitLobe;          // lobe of the first indirect ray: 0 none, 1 diffuse, 2 specular
};

// The diffuse lobe's bump-shadowing factor at v for light from wi (parameter bumpShadowing;
// compiled in only for scenes with normal textures, where ns can differ from nSmooth).
float bumpShadowing(Vertex v, vec3 wi) {
#if PATHTRACE_BUMP_SHADOWING
    return brdfBumpShadowing(v.nSmooth, v.ns, wi);
#else
    return 1.0;
#endif
}

// Next-event estimation at v; `last` = no BRDF ray follows (full weight, see header). Returns the
// contribution of each lobe (their sum is the estimate).
void nextEvent(Vertex v, uint vertex, bool last, out vec3 diffusePart, out vec3 specularPart) {
    diffusePart = vec3(0.0);
    specularPart = vec3(0.0);
    SceneLightSample ls;
    vec3 p = bvhOffsetRay(v.position, v.ng);
#if PATHTRACE_STRATIFY_LIGHT
    vec4 u = vertex == 1u ? primaryLightSample()
                          : vec4(rand(vertex, kDimLight), rand(vertex, kDimLight + 1u),
                                 rand(vertex, kDimLight + 2u), rand(vertex, kDimLight + 3u));
#else
    vec4 u = vec4(rand(vertex, kDimLight), rand(vertex, kDimLight + 1u),
                  rand(vertex, kDimLight + 2u), rand(vertex, kDimLight + 3u));
#endif
    if (!sceneSampleLight(p, u, ls)) return;
    float cosS = dot(v.ns, ls.direction);
    if (cosS <= 0.0 || dot(v.ng, ls.direction) <= 0.0) return;
    vec3 fd, fs;
    brdfEvalLobes(v.brdf, v.ns, v.wo, ls.direction, bumpShadowing(v, ls.direction), fd, fs);
    if (maxComponent(fd + fs) <= 0.0) return;
    // `last` is false for every vertex when the last one also traces a BRDF ray (LAST_RAY).
    float w = ls.isDelta ? 1.0
                         : lightSampleWeight(ls.pdf, brdfPdf(v.brdf, v.ns, v.wo, ls.direction),
                                             !last);
    if (w <= 0.0) return;
    COUNT_RAY(vertex == 1u ? 1 : 3);
    if (bvhOccluded(p, ls.direction, 0.0, ls.distance * kShadowShorten, alphaSeed(vertex, 0u)))
        return;
    vec3 li = cosS * ls.radiance * (w / ls.pdf);  // ls.pdf > 0 when sampleLight succeeds
    diffusePart = fd * li;
    specularPart = fs * li;
}

// Light x reaching vertex `depth` (already MIS-weighted), seen through the path throughput
// tD + tS (its parts through the primary vertex's diffuse and specular lobes): light after one
// reflection is direct, later light indirect (clamped when clampIndirect is set; the split parts
// are scaled alike).
void addFound(inout PathResult r, int depth, vec3 tD, vec3 tS, vec3 x) {
    vec3 e = (tD + tS) * x;
    float k = 1.0;
    if (depth == 0) {
        r.direct += e;
    } else {
        vec3 c = clampContribution(e);
        float m = maxComponent(e);
        k = m > 0.0 ? maxComponent(c) / m : 1.0;  // m > 0
        r.indirect += c;
    }
    r.diffuse += tD * x * k;
    r.specular += tS * x * k;
}

PathResult tracePath(uvec2 pixel, bool haveVisibility, uvec4 vis) {
    PathResult r;
    r.direct = vec3(0.0);
    r.indirect = vec3(0.0);
    r.emission = vec3(0.0);
    r.albedo = vec3(0.0);
    r.hitT = 0.0;
    r.diffuse = vec3(0.0);
    r.specular = vec3(0.0);
    r.diffuseAlbedo = vec3(0.0);
    r.specularAlbedo = vec3(0.0);
    r.roughness = 1.0;
    r.viewZ = 0.0;
    r.hitLobe = 0;
    // The GBuffer's eye (bits 8..15): on a Visual-Polar grid the texel's column is not a screen
    // column (seed 003 P5 §3.2); on the screen grid both agree.
    uint eye = haveVisibility ? min((vis.w >> 8) & 0xFFu, cameraEyeCount() - 1u)
                              : cameraEyeOf(pixel.x);
    uint triangle;
    vec2 bary;
    vec3 dir;
    if (haveVisibility) {
        if ((vis.w & kVisHit) == 0u || vis.x == 0u) {
            // The GBuffer saw the sky: with an environment it left the ray's direction in
            // visibility.yz (octahedral), the background seen through this pixel.
            if (sceneHasEnvironment()) {
                r.emission = sceneEnvironmentRadiance(
                    octahedralDecode(vec2(uintBitsToFloat(vis.y), uintBitsToFloat(vis.z))));
                r.direct = r.emission;
            }
            return r;
        }
        triangle = vis.x - 1u;
        bary = vec2(uintBitsToFloat(vis.y), uintBitsToFloat(vis.z));
        SceneSurface s = sceneSurface(triangle, bary);
        vec3 toHit = s.position - camera_info.eyes[eye].position.xyz;
        float len = length(toHit);
        // The camera never sits on a visible surface (znear > 0); guard the division anyway.
        dir = len > 0.0 ? toHit / len : vec3(0.0, 0.0, -1.0);
    } else {
        // P2 §3.1 rasterizes primaries at the pixel centre; references antialias instead: a
        // uniform position inside the pixel per sample (box filter).
        vec2 jitter = vec2(rand(0u, kDimPixel), rand(0u, kDimPixel + 1u));
        vec3 origin;
        cameraRay(eye, vec2(pixel) + jitter, origin, dir);
        BvhHit hit;
        COUNT_RAY(0);
        if (!bvhClosestHit(origin, dir, 0.0, kInfinity, alphaSeed(0u, 1u), hit)) {
            r.emission = sceneEnvironmentRadiance(dir);  // the background (0 without one)
            r.direct = r.emission;
            return r;
        }
        triangle = hit.triangle;
        bary = hit.barycentrics;
    }
    Vertex v = makeVertex(triangle, bary, dir);
    r.albedo = v.brdf.baseColor;
    r.emission = v.emitted;
    r.direct = v.emitted;
    r.viewZ = cameraViewDepth(eye, v.position);
#if BRDF_GGX
    r.diffuseAlbedo = (1.0 - v.brdf.metallic) * v.brdf.baseColor;
    r.specularAlbedo = specularAlbedo(brdfF0(v.brdf), dot(v.ns, v.wo), v.brdf.roughness);
    r.roughness = v.brdf.roughness;
#else
    r.diffuseAlbedo = v.brdf.baseColor;
#endif
    // The path throughput split by the primary vertex's lobes (tD + tS); the primary vertex's
    // own light is split by brdfEvalLobes in nextEvent.
    vec3 tD = vec3(1.0), tS = vec3(0.0);
    int bounces = max(pc.maxBounces, 0);
    for (int depth = 0; depth <= bounces; ++depth) {
        uint vertex = uint(depth) + 1u;
        bool last = depth == bounces;
        vec3 neD, neS;
#if PATHTRACE_LAST_RAY
        // The last vertex traces a BRDF ray too, so its shadow ray is MIS-weighted as well.
        nextEvent(v, vertex, false, neD, neS);
#else
        nextEvent(v, vertex, last, neD, neS);
#endif
        if (depth == 0) {
            r.direct += neD + neS;
            r.diffuse += neD;
            r.specular += neS;
        } else {
            addFound(r, depth, tD, tS, neD + neS);
        }
#if !PATHTRACE_LAST_RAY
        if (last) break;
#endif

        vec3 u = vec3(rand(vertex, kDimBrdf), rand(vertex, kDimBrdf + 1u),
                      rand(vertex, kDimBrdf + 2u));
        vec3 wi;
        bool specularLobe;
        if (!brdfSampleLobe(v.brdf, v.ns, v.wo, u, wi, specularLobe)) break;
        if (dot(wi, v.ng) <= 0.0) break;  // below the geometric surface: would leak light
        float brdfPdfValue = brdfPdf(v.brdf, v.ns, v.wo, wi);
        vec3 wD, wS;
        brdfWeightLobes(v.brdf, v.ns, v.wo, wi, bumpShadowing(v, wi), wD, wS);
        if (depth == 0) {
            tD = wD;
            tS = wS;
            r.hitLobe = specularLobe ? 2 : 1;
        } else {
            tD *= wD + wS;
            tS *= wD + wS;
        }
        if (maxComponent(tD + tS) <= 0.0) break;
        vec3 p = bvhOffsetRay(v.position, v.ng);
        BvhHit hit;
#if PATHTRACE_LAST_RAY
        COUNT_RAY(last ? 4 : 2);
        if (!bvhClosestHit(p, wi, 0.0, kInfinity, alphaSeed(vertex, 1u), hit)) {
            addFound(r, depth, tD, tS, escapedRadiance(wi, brdfPdfValue));
            break;
        }
        if (depth == 0 && !last) r.hitT = hit.t;  // hit_distance: the first *indirect* ray
        if (last) {
            // Only the emission this ray finds counts: the path ends here (no shading of the
            // hit, no further shadow ray).
            SceneSurface hs = sceneSurface(hit.triangle, hit.barycentrics);
            vec3 le = sceneEmission(hs.material, hs.uv, dot(hs.geometricNormal, wi) < 0.0);
            if (maxComponent(le) > 0.0) {
                float lightPdf = sceneEmitterPdf(hit.triangle, p, hs.position);
                addFound(r, depth, tD, tS, le * brdfHitWeight(brdfPdfValue, lightPdf));
            }
            break;
        }
#else
        COUNT_RAY(2);
        if (!bvhClosestHit(p, wi, 0.0, kInfinity, alphaSeed(vertex, 1u), hit)) {
            addFound(r, depth, tD, tS, escapedRadiance(wi, brdfPdfValue));
            break;
        }
        if (depth == 0) r.hitT = hit.t;
#endif
        Vertex next = makeVertex(hit.triangle, hit.barycentrics, wi);
        if (maxComponent(next.emitted) > 0.0) {
            // The light-sampling strategy could have produced this direction too (MIS).
            float lightPdf = sceneEmitterPdf(hit.triangle, p, next.position);
            addFound(r, depth, tD, tS, next.emitted * brdfHitWeight(brdfPdfValue, lightPdf));
        }
        v = next;
    }
    return r;
}

void main() {
    uvec2 pixel;
    uint samples;
    uvec2 imageSize = uvec2(pc.size);
    if (!sampleLayoutWorkItem(pc.useLayout != 0, gl_GlobalInvocationID.xy, imageSize,
                              uint(max(pc.spp, 0)), pixel, samples))
        return;
    uvec4 vis = pc.useVisibility != 0 ? imageLoad(visibility, ivec2(pixel)) : uvec4(0u);
    // A Visual-Polar texel outside the grid's traced area (fovea clip, off screen): no sample.
    if (pc.useVisibility != 0 && (vis.w & kVisClipped) != 0u) {
        ivec2 q = ivec2(pixel);
        imageStore(radiance, q, vec4(0.0));
        imageStore(demodulated, q, vec4(0.0));
        imageStore(hit_distance, q, vec4(0.0));
        imageStore(direct, q, vec4(0.0));
        imageStore(indirect, q, vec4(0.0));
        imageStore(diffuse, q, vec4(0.0));
        imageStore(specular, q, vec4(0.0));
        imageStore(diffuse_hit, q, vec4(-1.0));
        imageStore(specular_hit, q, vec4(-1.0));
        imageStore(diffuse_albedo, q, vec4(0.0));
        imageStore(specular_albedo, q, vec4(0.0));
        return;
    }
    // A pixel the GBuffer did not trace (bit 0 clear) falls back to own primary rays.
    bool haveVisibility = pc.useVisibility != 0 && (vis.w & kVisTraced) != 0u;

    uint pixelSeed = hashCombine(hashCombine(pcgHash(pc.seedLo), pc.seedHi),
                                 pixel.y * uint(pc.size.x) + pixel.x);
    pixelSeed = hashCombine(pixelSeed, camera_info.frame.x);

    vec3 sumDirect = vec3(0.0), sumIndirect = vec3(0.0), sumEmission = vec3(0.0);
    vec3 sumAlbedo = vec3(0.0);
    float sumT = 0.0;
    uint hits = 0u;
    vec3 sumDiffuse = vec3(0.0), sumSpecular = vec3(0.0);
    vec3 sumDiffuseAlbedo = vec3(0.0), sumSpecularAlbedo = vec3(0.0);
    vec2 sumH = vec2(0.0), lobeRays = vec2(0.0);  // per lobe: normalized hit distances, rays
    for (uint s = 0u; s < samples; ++s) {
        gSampleSeed = hashCombine(pixelSeed, s);
#if PATHTRACE_STRATIFY_LIGHT
        gPixelSeed = pixelSeed;
        gSampleIndex = s;
#endif
        PathResult r = tracePath(pixel, haveVisibility, vis);
        // A non-finite sample (degenerate data) contributes nothing rather than poisoning the
        // pixel; it still counts as traced.
        sumDirect += finiteOrZero(r.direct);
        sumIndirect += finiteOrZero(r.indirect);
        sumEmission += finiteOrZero(r.emission);
        sumAlbedo += finiteOrZero(r.albedo);
        if (r.hitT > 0.0 && !isinf(r.hitT)) {
            sumT += r.hitT;
            ++hits;
        }
        sumDiffuse += finiteOrZero(r.diffuse);
        sumSpecular += finiteOrZero(r.specular);
        sumDiffuseAlbedo += finiteOrZero(r.diffuseAlbedo);
        sumSpecularAlbedo += finiteOrZero(r.specularAlbedo);
        if (r.hitLobe > 0 && r.viewZ > 0.0) {
            // The lobe's own first indirect ray; a miss (hitT 0) is far (h = 1).
            float roughness = r.hitLobe == 2 ? r.roughness : 1.0;
            float h = normalizeHitDistance(
                r.hitT, hitDistanceScale(camera_info.jitter.z, r.viewZ, roughness));
            sumH[r.hitLobe - 1] += h;
            lobeRays[r.hitLobe - 1] += 1.0;
        }
    }
#if PATHTRACE_COUNT_RAYS
    for (int k = 0; k < kRayKinds; ++k)
        if (gRays[k] > 0u) atomicAdd(pathtrace_rays.counts[k], gRays[k]);
#endif
    float n = float(samples);  // >= 1: sampleLayoutWorkItem returns false for 0 samples
    vec3 dir = sumDirect / n;
    vec3 ind = sumIndirect / n;
    vec3 rad = dir + ind;
    vec3 emission = sumEmission / n;
    vec3 alb = pc.useAlbedo != 0 ? texelFetch(albedo, ivec2(pixel), 0).rgb : sumAlbedo / n;
    vec3 safeAlbedo = mix(vec3(1.0), alb, greaterThan(alb, vec3(kAlbedoEpsilon)));
    vec3 demod = (rad - emission) / safeAlbedo;  // each channel > 1e-3 or exactly 1
    ivec2 p = ivec2(pixel);
    imageStore(radiance, p, vec4(rad, n));
    imageStore(demodulated, p, vec4(finiteOrZero(demod), n));
    imageStore(hit_distance, p, vec4(hits > 0u ? sumT / float(hits) : 0.0));  // hits >= 1
    // rgba16f saturates at 65504: clamp so a bright pixel stays finite instead of becoming inf.
    imageStore(direct, p, vec4(min(dir, vec3(kHalfMax)), n));
    imageStore(indirect, p, vec4(min(ind, vec3(kHalfMax)), n));
    // The split signals, each demodulated by its own albedo' (same epsilon rule); *_hit = the
    // mean normalized hit distance of the lobe's rays (1 = far or missed, -1 = no ray).
    vec3 dAlb = sumDiffuseAlbedo / n, sAlb = sumSpecularAlbedo / n;
    vec3 dSafe = mix(vec3(1.0), dAlb, greaterThan(dAlb, vec3(kAlbedoEpsilon)));
    vec3 sSafe = mix(vec3(1.0), sAlb, greaterThan(sAlb, vec3(kAlbedoEpsilon)));
    // -1: no ray of that lobe here ("no data": at 1 spp most pixels trace one lobe only).
    vec2 h = mix(vec2(-1.0), sumH / max(lobeRays, vec2(1.0)), greaterThan(lobeRays, vec2(0.0)));
    imageStore(diffuse, p, vec4(finiteOrZero(sumDiffuse / n / dSafe), n));  // dSafe >= 1e-3
    imageStore(specular, p, vec4(finiteOrZero(sumSpecular / n / sSafe), n));
    imageStore(diffuse_hit, p, vec4(h.x));
    imageStore(specular_hit, p, vec4(h.y));
    imageStore(diffuse_albedo, p, vec4(min(dAlb, vec3(kHalfMax)), n));
    imageStore(specular_albedo, p, vec4(min(sAlb, vec3(kHalfMax)), n));
}
