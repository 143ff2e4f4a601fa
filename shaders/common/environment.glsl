// Environment light on the GPU: the radiance of an equirectangular map seen in a direction, its
// importance sampling and the matching solid-angle pdf. The CPU reference, the direction
// convention and the derivation of the pdf are in core/scene/Environment.h (pbrt-v3 §14.2.4);
// tests/unit/EnvironmentTests.cpp checks the CPU side, tests/graph/EnvironmentLightTests.cpp this
// one against analytic values. All functions return "no environment" (zero radiance, pdf 0,
// false) when the scene has none, so callers need no #if.
#ifndef FOVEA_ENVIRONMENT_GLSL
#define FOVEA_ENVIRONMENT_GLSL

#include "scene_data.glsl"

const float kEnvironmentPi = 3.14159265358979;

bool sceneHasEnvironment() {
#if SCENE_HAS_ENVIRONMENT
    return scene_environment.width > 0u && scene_environment.height > 0u;
#else
    return false;
#endif
}

// Octahedral encoding of a unit vector into [-1, 1]^2 (Cigolle et al. 2014, "A Survey of
// Efficient Representations for Independent Unit Vectors", §3.2): how GBuffer hands a miss's ray
// direction to PathTrace in visibility.yz. |x| + |y| + |z| >= 1 for a unit vector: no division by
// zero; sign() of 0 is taken as +1 so the fold stays a bijection on the axes.
vec2 octahedralEncode(vec3 d) {
    vec3 a = abs(d);
    vec2 p = d.xy / max(a.x + a.y + a.z, 1e-20);
    if (d.z < 0.0) {
        vec2 s = vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
        p = (1.0 - abs(p.yx)) * s;
    }
    return p;
}
vec3 octahedralDecode(vec2 p) {
    vec3 d = vec3(p, 1.0 - abs(p.x) - abs(p.y));
    if (d.z < 0.0) {
        vec2 s = vec2(d.x >= 0.0 ? 1.0 : -1.0, d.y >= 0.0 ? 1.0 : -1.0);
        d.xy = (1.0 - abs(d.yx)) * s;
    }
    float len = length(d);  // >= 1 / sqrt(3) for any p: |x| + |y| + |z| = 1 after the fold
    return d / len;
}

#if SCENE_HAS_ENVIRONMENT
// (u, v) in [0, 1)^2 of unit direction d: theta = acos(y), phi = atan2(z, x) + rotation.
// atan(0, 0) is undefined in GLSL: the poles take phi = 0.
vec2 environmentUv(vec3 d) {
    float phi = (d.x == 0.0 && d.z == 0.0) ? 0.0 : atan(d.z, d.x);
    float u = fract(0.5 + (phi + scene_environment.rotation) / (2.0 * kEnvironmentPi));
    float v = acos(clamp(d.y, -1.0, 1.0)) / kEnvironmentPi;
    // fract may round up to 1.0 for tiny negative arguments: stay inside the last texel.
    return min(vec2(u, v), vec2(0.99999994));
}

uint environmentTexelOf(vec2 uv) {
    uint w = scene_environment.width, h = scene_environment.height;
    uint i = min(uint(uv.x * float(w)), w - 1u);
    uint j = min(uint(uv.y * float(h)), h - 1u);
    return j * w + i;
}

// Alias draw among n slots starting at `first`: slot from `slot` in [0, 1), kept with the slot's
// probability against `coin`, else its alias. Returns the index within the table.
uint environmentAliasDraw(uint first, uint n, float slot, float coin) {
    uint s = min(uint(slot * float(n)), n - 1u);
    uvec2 entry = scene_environment_alias.alias[first + s];
    return coin < uintBitsToFloat(entry.y) ? s : entry.x;
}
#endif

// Radiance arriving from unit direction `dir` (nearest texel: the pdf is constant per texel,
// and a bilinear lookup would give light where the pdf is 0 next to black texels).
vec3 sceneEnvironmentRadiance(vec3 dir) {
#if SCENE_HAS_ENVIRONMENT
    if (!sceneHasEnvironment()) return vec3(0.0);
    return scene_environment.texels[environmentTexelOf(environmentUv(dir))].rgb;
#else
    return vec3(0.0);
#endif
}

// Solid-angle pdf with which sceneSampleLight produces unit direction `dir` through the
// environment, its selection probability included (for MIS after a BRDF ray escapes).
float sceneEnvironmentPdf(vec3 dir) {
#if SCENE_HAS_ENVIRONMENT
    if (!sceneHasEnvironment()) return 0.0;
    vec2 uv = environmentUv(dir);
    float sinTheta = sin(kEnvironmentPi * uv.y);
    // At the poles the map's texels have no area: never sampled there (pdf 0).
    if (!(sinTheta > 0.0)) return 0.0;
    float p = scene_environment.texels[environmentTexelOf(uv)].a;
    return scene_environment.selectProbability * p * scene_environment.pdfScale / sinTheta;
#else
    return 0.0;
#endif
}

// A direction drawn from the environment's distribution: u.x picks the row (u.y keeps it or
// takes its alias), u.z the column within the row (u.w likewise), and the leftover fractions of
// u.x and u.z place the direction inside the texel (uniform in u, v). pdf includes the
// selection probability. False without an environment or for a sample at a pole.
bool sceneSampleEnvironment(vec4 u, out vec3 direction, out vec3 radiance, out float pdf) {
    direction = vec3(0.0, 1.0, 0.0);
    radiance = vec3(0.0);
    pdf = 0.0;
#if SCENE_HAS_ENVIRONMENT
    if (!sceneHasEnvironment()) return false;
    uint w = scene_environment.width, h = scene_environment.height;
    uint j = environmentAliasDraw(0u, h, u.x, u.y);
    uint i = environmentAliasDraw(h + j * w, w, u.z, u.w);
    // The fraction of the slot number left after the slot was chosen is uniform in [0, 1) and
    // independent of the choice (about 24 - log2(n) bits of it: >= 11 bits for n <= 8192).
    vec2 inside = fract(vec2(u.x * float(h), u.z * float(w)));
    vec2 uv = (vec2(float(i), float(j)) + inside.yx) / vec2(float(w), float(h));
    float theta = kEnvironmentPi * uv.y;
    float phi = 2.0 * kEnvironmentPi * (uv.x - 0.5) - scene_environment.rotation;
    float sinTheta = sin(theta);
    if (!(sinTheta > 0.0)) return false;
    direction = vec3(sinTheta * cos(phi), cos(theta), sinTheta * sin(phi));
    vec4 t = scene_environment.texels[j * w + i];
    radiance = t.rgb;
    pdf = scene_environment.selectProbability * t.a * scene_environment.pdfScale / sinTheta;
    return pdf > 0.0;
#else
    return false;
#endif
}

#endif
