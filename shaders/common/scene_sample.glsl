// Shading-side scene queries: surface attributes at a hit, material lookup (texture filtering in
// scene_texture.glsl: textures live in one texel buffer, see docs/scene-gpu.md), normal maps,
// alpha coverage, light sampling through the alias table (and the environment) and punctual
// light evaluation.
//
// Light sampling contract: for a sample s from sceneSampleLight, the direct-light estimate at a
// point with BSDF f and normal n is
//     f * |dot(n, s.direction)| * s.radiance / s.pdf      (if the shadow ray is unoccluded)
// s.pdf includes the light's selection probability; for area lights it is a solid-angle pdf
// (MIS against BSDF sampling with sceneEmitterPdf), for punctual lights (s.isDelta) it is the
// selection probability alone and s.radiance is the incident intensity / distance^2.
#ifndef FOVEA_SCENE_SAMPLE_GLSL
#define FOVEA_SCENE_SAMPLE_GLSL

#include "environment.glsl"
#include "scene_data.glsl"
#include "scene_texture.glsl"
#if SCENE_HAS_ALPHA
#include "random.glsl"
#endif

const float kSceneInfiniteDistance = 1e30;  // shadow-ray tMax of directional lights
const uint kSceneEnvironmentLight = 0xFFFFFFFFu;  // SceneLightSample.light of the environment

// The probability that next-event estimation samples the environment rather than the alias table
// of the scene's other lights (SceneGpu: by power; 1 when nothing else emits, 0 without one).
// Every pdf of those other lights is scaled by 1 - this (sceneSampleLight, sceneEmitterPdf).
float sceneEnvironmentSelectProbability() {
#if SCENE_HAS_ENVIRONMENT
    return sceneHasEnvironment() ? scene_environment.selectProbability : 0.0;
#else
    return 0.0;
#endif
}

// SCENE_LIGHT_SOLID_ANGLE 1 (PathTrace's lightSampling = solidAngle): a sampled emissive
// triangle yields a direction uniform in the solid angle it subtends (Arvo 1995) instead of a
// uniform point on its area, so the d^2 / (A cos) factor of area sampling, heavy-tailed next to
// the light, never enters the estimate. Triangles subtending less than kSceneMinSolidAngle
// (where the float formulas below lose their digits) or more than kSceneMaxSolidAngle (close
// to a hemisphere, where the inversion loses precision; pbrt-v4 uses similar bounds) keep area
// sampling; sceneSampleLight and sceneEmitterPdf make the same choice from the same solid
// angle, so MIS stays consistent.
#ifndef SCENE_LIGHT_SOLID_ANGLE
#define SCENE_LIGHT_SOLID_ANGLE 0
#endif
#if SCENE_LIGHT_SOLID_ANGLE
const float kSceneMinSolidAngle = 3e-4;
const float kSceneMaxSolidAngle = 6.0;
const float kScenePi = 3.14159265358979;

// Solid angle of the triangle with corners a, b, c relative to the viewpoint (Van Oosterom and
// Strackee 1983): tan(omega / 2) = |a.(b x c)| / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|).
// atan(y, x) takes any sign of the denominator (omega > pi); it is undefined for 0 / 0, so a
// triangle seen edge-on or from one of its corners (numerator 0) returns 0 first.
float sceneTriangleSolidAngle(vec3 a, vec3 b, vec3 c) {
    float la = length(a), lb = length(b), lc = length(c);
    float numerator = abs(dot(a, cross(b, c)));
    if (!(numerator > 0.0)) return 0.0;
    float denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    return 2.0 * atan(numerator, denominator);
}

bool sceneUseSolidAngle(float omega) {
    return omega >= kSceneMinSolidAngle && omega <= kSceneMaxSolidAngle;
}

// Angle between unit vectors, accurate near 0 and pi too (acos of the dot product loses half
// the digits there): 2 asin of half the chord. asin's argument is <= 1 up to rounding: clamped.
float sceneAngleBetween(vec3 p, vec3 q) {
    return dot(p, q) < 0.0 ? kScenePi - 2.0 * asin(min(1.0, 0.5 * length(p + q)))
                           : 2.0 * asin(min(1.0, 0.5 * length(p - q)));
}

// Direction uniform in the spherical triangle (A, B, C) of unit vectors with solid angle `area`
// (Arvo 1995, "Stratified Sampling of Spherical Triangles", Fig. 2): u.x picks the sub-triangle
// A B C' of area u.x * area, which fixes C' on the arc AC; u.y the point on the arc B C'. The
// area comes from sceneTriangleSolidAngle, not from the spherical excess alpha + beta + gamma -
// pi: for a sliver seen almost edge-on (the ceiling next to a light) that difference cancels to
// a few digits, and a too small area would leave part of the triangle unsampled (a bias). False
// for a degenerate triangle.
bool sceneSampleSphericalTriangle(vec3 A, vec3 B, vec3 C, float area, vec2 u, out vec3 w) {
    w = A;
    if (!(area > 0.0)) return false;
    vec3 nAB = cross(A, B), nCA = cross(C, A);
    float lAB = length(nAB), lBC = length(cross(B, C)), lCA = length(nCA);
    if (!(lAB > 0.0 && lBC > 0.0 && lCA > 0.0)) return false;  // an edge of zero length
    // The interior angle at A: between the planes of the two edges meeting there.
    float alpha = sceneAngleBetween(nAB / lAB, -nCA / lCA);  // lengths > 0 checked above
    float areaSub = u.x * area;
    float s = sin(areaSub - alpha), t = cos(areaSub - alpha);
    float cosAlpha = cos(alpha), sinAlpha = sin(alpha);
    float uu = t - cosAlpha;
    float vv = s + sinAlpha * dot(A, B);  // dot(A, B) = cos of the arc c opposite C
    float denominator = (vv * s + uu * t) * sinAlpha;
    // Zero only on a measure-zero set of u.x: drop that sample (it would divide by 0).
    if (denominator == 0.0) return false;
    // q = cos of the arc A C'; C' lies on the arc A C, so q is in [A.C, 1]. Float rounding in
    // the formula can put it slightly past C (a direction just outside the triangle): clamped.
    float q = clamp(((vv * t - uu * s) * cosAlpha - vv) / denominator, dot(A, C), 1.0);
    vec3 cPerp = C - dot(C, A) * A;
    float cPerpLen = length(cPerp);
    if (!(cPerpLen > 0.0)) return false;  // C parallel to A: the arc AC has no direction
    vec3 cPrime = q * A + sqrt(max(0.0, 1.0 - q * q)) * (cPerp / cPerpLen);
    float z = 1.0 - u.y * (1.0 - dot(cPrime, B));
    vec3 pPerp = cPrime - dot(cPrime, B) * B;
    float pPerpLen = length(pPerp);
    // C' = B (the arc B C' has zero length): every u.y gives B itself.
    w = pPerpLen > 0.0 ? z * B + sqrt(max(0.0, 1.0 - z * z)) * (pPerp / pPerpLen) : B;
    w = normalize(w);  // unit up to rounding; never zero (z^2 + (1 - z^2) = 1)
    return true;
}
#endif

struct SceneSurface {
    vec3 position;         // interpolated from the vertices (more precise than origin + t * dir)
    vec3 geometricNormal;  // normalized; the front side of the CCW winding (glTF)
    vec3 normal;           // interpolated shading normal, normalized (geometric where missing);
                           // not flipped towards the ray: compare with geometricNormal
    vec2 uv;
    uint material;
    float area;   // of the triangle
    vec4 color;   // glTF COLOR_0, interpolated (1 without vertex colours)
    uint triangle;       // the hit, for what only some callers need (sceneApplyNormalMap)
    vec2 barycentrics;
};

struct SceneMaterialSample {
    vec3 baseColor;  // linear
    float alpha;
    vec3 emissive;  // linear radiance of the front face (sceneEmission handles back faces)
    float metallic;
    float roughness;
    bool doubleSided;
};

struct SceneLightSample {
    vec3 direction;  // unit vector from the shaded point to the light
    float distance;  // to the light point: the shadow ray's tMax (shorten it by an epsilon)
    vec3 radiance;   // area: emitted radiance towards the point; punctual: intensity / d^2
    float pdf;       // see the contract above; > 0 whenever sceneSampleLight returns true
    bool isDelta;    // punctual light: no MIS, BSDF rays never hit it
    uint light;      // the SceneEmitter.light value that was picked; kSceneEnvironmentLight for
                     // the environment
};

#if SCENE_HAS_VERTEX_COLORS
// White without colours: a shader compiled without defines (everything on) may run on a scene
// whose scene_vertex_colors is a 16-byte dummy.
vec4 sceneVertexColor(uint vertex) {
    if (scene_info.vertexColors == 0u || vertex >= scene_info.vertexCount) return vec4(1.0);
    uvec2 p = scene_vertex_colors.colors[vertex];
    return vec4(unpackUnorm2x16(p.x), unpackUnorm2x16(p.y));
}
#endif

// Vertex 0 gets 1 - b.x - b.y.
SceneSurface sceneSurface(uint triangle, vec2 barycentrics) {
    SceneTriangle tri = sceneTriangle(triangle);
    SceneVertex a = sceneVertex(tri.indices.x);
    SceneVertex b = sceneVertex(tri.indices.y);
    SceneVertex c = sceneVertex(tri.indices.z);
    vec3 w = vec3(1.0 - barycentrics.x - barycentrics.y, barycentrics.x, barycentrics.y);
    SceneSurface s;
    s.position = a.positionU.xyz * w.x + b.positionU.xyz * w.y + c.positionU.xyz * w.z;
    vec3 cr = cross(b.positionU.xyz - a.positionU.xyz, c.positionU.xyz - a.positionU.xyz);
    float len = length(cr);
    // A hit triangle has nonzero area (the intersection rejects degenerate ones); the fallback
    // only keeps callers with arbitrary ids NaN-free.
    s.geometricNormal = len > 0.0 ? cr / len : vec3(0.0, 0.0, 1.0);
    s.area = 0.5 * len;
    vec3 n = a.normalV.xyz * w.x + b.normalV.xyz * w.y + c.normalV.xyz * w.z;
    float nLen = length(n);
    // Zero when the mesh has no normals, or opposite normals cancel: use the geometric one.
    s.normal = nLen > 1e-20 ? n / nLen : s.geometricNormal;
    s.uv = vec2(a.positionU.w, a.normalV.w) * w.x + vec2(b.positionU.w, b.normalV.w) * w.y +
           vec2(c.positionU.w, c.normalV.w) * w.z;
    s.material = tri.material;
#if SCENE_HAS_VERTEX_COLORS
    // Written as ca + (cb - ca) b.x + (cc - ca) b.y: a constant colour (e.g. white) comes out
    // exactly, so scenes whose COLOR_0 is all 1 render bit for bit as without it.
    vec4 ca = sceneVertexColor(tri.indices.x);
    s.color = ca + (sceneVertexColor(tri.indices.y) - ca) * barycentrics.x +
              (sceneVertexColor(tri.indices.z) - ca) * barycentrics.y;
#else
    s.color = vec4(1.0);
#endif
    s.triangle = triangle;
    s.barycentrics = barycentrics;
    return s;
}

SceneMaterialSample sceneMaterial(uint material, vec2 uv) {
    SceneMaterial m = scene_materials.materials[material];
    SceneMaterialSample s;
    vec4 base =
        m.baseColor * sceneSampleMaterialTexture(material, kSceneSlotBaseColor, m.textures.x, uv,
                                                 true);
    s.baseColor = base.rgb;
    s.alpha = base.a;
    // glTF: G = roughness, B = metallic
    vec4 mr =
        sceneSampleMaterialTexture(material, kSceneSlotMetallicRoughness, m.textures.y, uv, false);
    s.metallic = m.params.x * mr.b;
    s.roughness = m.params.y * mr.g;
    s.doubleSided = m.params.z != 0.0;
#if SCENE_HAS_EMISSIVE
    s.emissive = m.emissive.rgb *
                 sceneSampleMaterialTexture(material, kSceneSlotEmissive, m.textures.z, uv, true).rgb;
#else
    s.emissive = vec3(0.0);  // nothing in the scene emits
#endif
    return s;
}

// The material at a surface: sceneMaterial with the base colour (and alpha) multiplied by the
// interpolated vertex colour, as glTF 2.0 §3.9.2 defines baseColor = factor * texture * COLOR_0.
// What every pass that shades or writes albedo calls (GBuffer, PathTrace).
SceneMaterialSample sceneSurfaceMaterial(SceneSurface s) {
    SceneMaterialSample m = sceneMaterial(s.material, s.uv);
    m.baseColor *= s.color.rgb;
    m.alpha *= s.color.a;
    return m;
}

// glTF 2.0 §3.9.3: the shading normal from the material's tangent-space normal texture,
// n_t = (2 rgb - 1) * (scale, scale, 1), N' = normalize(T n_t.x + B n_t.y + N n_t.z) with T the
// interpolated tangent made perpendicular to N and B = cross(N, T) * w. Replaces s.normal (front
// side, like the interpolated normal; callers flip it for back faces as before). GBuffer and
// PathTrace call it before shading; the geometric normal stays for ray offsets and leak checks.
// A degenerate frame or texel keeps the interpolated normal.
void sceneApplyNormalMap(inout SceneSurface s) {
#if SCENE_HAS_NORMAL_MAPS && SCENE_HAS_TEXTURES
    // textures.w >= 0 only when scene_tangents holds one frame per vertex (SceneGpu).
    int texture = scene_materials.materials[s.material].textures.w;
    if (texture < 0) return;
    uvec3 corners = sceneTriangle(s.triangle).indices;
    vec3 w = vec3(1.0 - s.barycentrics.x - s.barycentrics.y, s.barycentrics);
    vec4 tangent = scene_tangents.tangents[corners.x] * w.x +
                   scene_tangents.tangents[corners.y] * w.y +
                   scene_tangents.tangents[corners.z] * w.z;
    vec3 t = tangent.xyz - s.normal * dot(s.normal, tangent.xyz);
    float tLength = length(t);
    if (!(tLength > 1e-8)) return;  // no tangent frame here
    t /= tLength;
    vec3 b = cross(s.normal, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
    SceneTextureView v =
        scene_texture_views.views[s.material * kSceneTextureSlots + kSceneSlotNormal];
    vec3 nt = sceneSampleMaterialTexture(s.material, kSceneSlotNormal, texture, s.uv, false).xyz;
    nt = nt * 2.0 - 1.0;
    nt.xy *= v.scale;
    vec3 n = t * nt.x + b * nt.y + s.normal * nt.z;
    float nLength = length(n);
    if (!(nLength > 1e-8)) return;  // a (0.5, 0.5, 0.5) texel encodes no direction
    s.normal = n / nLength;
#endif
}

#if SCENE_HAS_ALPHA
// --- Alpha coverage (glTF 2.0 §3.9.4), the any-hit test of bvh.glsl --------------------------
// A ray passes through a texel of an alpha-tested material when alpha < threshold, alpha being
// §3.9.2's baseColorFactor.a x baseColorTexture.a x COLOR_0.a. The threshold is params.w: MASK's
// alphaCutoff, or for BLEND 1 - u with u uniform in [0, 1) hashed from (the ray's seed, the
// triangle), so the ray passes with probability P(alpha < 1 - u) = 1 - alpha: stochastic
// transparency, noisy per frame and converging to the alpha-blended image in expectation
// (docs/scenes.md "Alpha"). Each ray hashes its own seed, each surface it meets gets its own u.

// Alpha at barycentrics b of `triangle` with material m: the operations of sceneSurface and
// sceneSurfaceMaterial in the same order (so shading and the test agree), reading only what
// alpha needs (the uv and COLOR_0.a, no normals, no sRGB decode: alpha is linear).
float sceneAlphaOf(SceneTriangle tri, SceneMaterial m, vec2 b) {
    float alpha = m.baseColor.a;
#if SCENE_HAS_TEXTURES
    if (m.textures.x >= 0) {
        SceneVertex va = sceneVertex(tri.indices.x);
        SceneVertex vb = sceneVertex(tri.indices.y);
        SceneVertex vc = sceneVertex(tri.indices.z);
        vec3 w = vec3(1.0 - b.x - b.y, b.x, b.y);
        vec2 uv = vec2(va.positionU.w, va.normalV.w) * w.x +
                  vec2(vb.positionU.w, vb.normalV.w) * w.y +
                  vec2(vc.positionU.w, vc.normalV.w) * w.z;
        // Through the base colour's view (sampler, KHR_texture_transform) as shading reads it.
        alpha *= sceneSampleMaterialTexture(tri.material, kSceneSlotBaseColor, m.textures.x, uv,
                                            false)
                     .a;
    }
#endif
#if SCENE_HAS_VERTEX_COLORS
    float ca = sceneVertexColor(tri.indices.x).a;
    alpha *= ca + (sceneVertexColor(tri.indices.y).a - ca) * b.x +
             (sceneVertexColor(tri.indices.z).a - ca) * b.y;
#endif
    return alpha;
}

// True when a ray with this seed passes through `triangle` at barycentrics b. Opaque materials
// (threshold 0) never let a ray through and read no texel.
bool sceneAlphaPassesThrough(uint triangle, vec2 b, uint seed) {
    SceneTriangle tri = sceneTriangle(triangle);
    SceneMaterial m = scene_materials.materials[tri.material];
    float threshold = m.params.w;
    if (threshold == 0.0) return false;
    // u < 1, so a BLEND threshold lies in (0, 1]: alpha 1 never passes, alpha 0 always does.
    if (threshold < 0.0) threshold = 1.0 - uintToUnitFloat(hashCombine(seed, triangle));
    return sceneAlphaOf(tri, m, b) < threshold;
}

// The fraction of rays that stop at `triangle` at b: 1 opaque, 0 or 1 for MASK, alpha for
// BLEND. Light sampling weights an emitter's radiance by it, so next-event estimation sees the
// same emission as the rays that pass or stop at the emitter (MIS stays consistent).
float sceneAlphaCoverage(uint triangle, vec2 b) {
    SceneTriangle tri = sceneTriangle(triangle);
    SceneMaterial m = scene_materials.materials[tri.material];
    if (m.params.w == 0.0) return 1.0;
    float alpha = sceneAlphaOf(tri, m, b);
    if (m.params.w > 0.0) return alpha < m.params.w ? 0.0 : 1.0;
    return clamp(alpha, 0.0, 1.0);
}
#endif

// Radiance leaving a surface of this material; back faces emit only when double-sided.
vec3 sceneEmission(uint material, vec2 uv, bool frontFacing) {
#if SCENE_HAS_EMISSIVE
    SceneMaterial m = scene_materials.materials[material];
    if (m.emissive.w <= 0.0 || (!frontFacing && m.params.z == 0.0)) return vec3(0.0);
    return m.emissive.rgb *
           sceneSampleMaterialTexture(material, kSceneSlotEmissive, m.textures.z, uv, true).rgb;
#else
    return vec3(0.0);
#endif
}

// Solid-angle pdf with which sceneSampleLight produces the direction from `origin` to the
// point `lightPosition` on emissive triangle `triangle` (for MIS after a BSDF ray hit it).
// selection * d^2 / (area * |cos|) with selection = density * area / totalPower: area cancels.
// sceneTableEmitterPdf: within the alias table; sceneEmitterPdf: times the table's selection.
float sceneTableEmitterPdf(uint triangle, vec3 origin, vec3 lightPosition) {
#if SCENE_HAS_EMISSIVE
    SceneMaterial m = scene_materials.materials[sceneTriangle(triangle).material];
    if (m.emissive.w <= 0.0 || !(scene_info.totalPower > 0.0)) return 0.0;
    uint base = 3u * triangle;
    vec3 cr = cross(sceneBvhPosition(base + 1u).xyz,
                    sceneBvhPosition(base + 2u).xyz);
    vec3 toLight = lightPosition - origin;
#if SCENE_LIGHT_SOLID_ANGLE
    vec3 v0 = sceneBvhPosition(base).xyz - origin;
    float omega = sceneTriangleSolidAngle(v0, v0 + sceneBvhPosition(base + 1u).xyz,
                                          v0 + sceneBvhPosition(base + 2u).xyz);
    // selection / omega, selection = density * area / totalPower (omega >= kSceneMinSolidAngle)
    if (sceneUseSolidAngle(omega))
        return m.emissive.w * 0.5 * length(cr) / (scene_info.totalPower * omega);
#endif
    float d2 = dot(toLight, toLight);
    // |cos| * |cr| * d = |dot(cr, toLight)|; one product avoids two normalizations.
    float cosTimes = abs(dot(cr, toLight));
    if (!(cosTimes > 0.0)) return 0.0;  // grazing or degenerate: this direction is never sampled
    // pdf = density * d2 / (totalPower * |cos|) with |cos| = cosTimes / (|cr| * d).
    return m.emissive.w * d2 * length(cr) * sqrt(d2) / (scene_info.totalPower * cosTimes);
#else
    return 0.0;
#endif
}

float sceneEmitterPdf(uint triangle, vec3 origin, vec3 lightPosition) {
    return (1.0 - sceneEnvironmentSelectProbability()) *
           sceneTableEmitterPdf(triangle, origin, lightPosition);
}

#if SCENE_HAS_PUNCTUAL
// Incident intensity / d^2 (with range and cone falloff) from punctual light `index` at
// `position`, and the unit direction and distance to it. Zero when the point is on the light.
vec3 scenePunctualIncident(uint index, vec3 position, out vec3 direction, out float distance) {
    SceneLight l = scene_lights.lights[index];
    if (l.type == kLightDirectional) {
        direction = -l.direction;  // normalized on upload
        distance = kSceneInfiniteDistance;
        return l.intensity;
    }
    vec3 toLight = l.position - position;
    float d2 = dot(toLight, toLight);
    if (!(d2 > 0.0)) {  // shading point exactly on the light: no defined direction
        direction = vec3(0.0, 0.0, 1.0);
        distance = 0.0;
        return vec3(0.0);
    }
    distance = sqrt(d2);
    direction = toLight / distance;  // distance > 0 here
    float attenuation = 1.0 / d2;    // d2 > 0 here
    if (l.range > 0.0) {
        float r = distance / l.range;  // range > 0 here
        attenuation *= clamp(1.0 - r * r * r * r, 0.0, 1.0);  // KHR_lights_punctual window
    }
    if (l.type == kLightSpot) {
        float a = clamp(dot(l.direction, -direction) * l.spotScale + l.spotOffset, 0.0, 1.0);
        attenuation *= a * a;
    }
    return l.intensity * attenuation;
}
#endif

// Picks a light of the alias table (u.x column, u.y coin) and, for a triangle, a uniform point
// on it (u.zw); s.pdf within the table. False when the table is empty or the sample carries
// nothing (back face of a one-sided emitter, the point on the light itself, grazing angle).
bool sceneSampleTableLight(vec3 position, vec4 u, inout SceneLightSample s) {
#if SCENE_HAS_EMISSIVE || SCENE_HAS_PUNCTUAL
    uint n = scene_info.emitterCount;
    if (n == 0u) return false;
    uint column = min(uint(u.x * float(n)), n - 1u);
    SceneEmitter e = scene_emitters.emitters[column];
    if (!(u.y < e.aliasProb)) e = scene_emitters.emitters[e.alias];
    s.light = e.light;
    if ((e.light & kEmitterPunctualBit) != 0u) {
#if SCENE_HAS_PUNCTUAL
        s.isDelta = true;
        s.radiance = scenePunctualIncident(e.light & ~kEmitterPunctualBit, position, s.direction,
                                           s.distance);
        s.pdf = e.pdf;
        return e.pdf > 0.0 && s.distance > 0.0;
#else
        return false;
#endif
    }
#if SCENE_HAS_EMISSIVE
    uint base = 3u * e.light;
    vec3 v0 = sceneBvhPosition(base).xyz;
    vec3 e1 = sceneBvhPosition(base + 1u).xyz;
    vec3 e2 = sceneBvhPosition(base + 2u).xyz;
    vec3 cr = cross(e1, e2);
    float crLen = length(cr);
    float area = 0.5 * crLen;
#if SCENE_LIGHT_SOLID_ANGLE
    vec3 a = v0 - position;
    float omega = sceneTriangleSolidAngle(a, a + e1, a + e2);
    if (sceneUseSolidAngle(omega) && crLen > 0.0) {
        vec3 w;
        // omega >= kSceneMinSolidAngle > 0: no corner is at the shaded point (lengths > 0)
        if (!sceneSampleSphericalTriangle(normalize(a), normalize(a + e1), normalize(a + e2),
                                          omega, u.zw, w))
            return false;
        // Where w meets the triangle's plane, and that point's barycentrics (for the emission
        // texture and the front/back test).
        float wn = dot(cr, w);
        if (!(abs(wn) > 0.0)) return false;  // grazing: w lies in the plane
        float t = dot(cr, a) / wn;
        if (!(t > 0.0)) return false;
        vec3 q = w * t - a;  // lightPos - v0
        float d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2);
        float det = d00 * d11 - d01 * d01;  // = |cr|^2 > 0
        float qe1 = dot(q, e1), qe2 = dot(q, e2);
        vec2 bary = vec2(d11 * qe1 - d01 * qe2, d00 * qe2 - d01 * qe1) / det;
        bary = clamp(bary, 0.0, 1.0);
        float cosLight = -wn / crLen;  // crLen > 0
        SceneSurface surf = sceneSurface(e.light, bary);
        s.radiance = sceneEmission(surf.material, surf.uv, cosLight > 0.0);
#if SCENE_HAS_ALPHA
        s.radiance *= sceneAlphaCoverage(e.light, bary);
#endif
        if (all(equal(s.radiance, vec3(0.0)))) return false;
        s.direction = w;
        s.distance = t;
        s.pdf = e.pdf / omega;  // selection x uniform solid-angle density
        return s.pdf > 0.0;
    }
#endif
    // Uniform on the triangle: b1 = sqrt(u.z) (1 - u.w), b2 = sqrt(u.z) u.w.
    float su = sqrt(u.z);  // u.z >= 0
    vec2 bary = vec2(su * (1.0 - u.w), su * u.w);
    vec3 lightPos = v0 + e1 * bary.x + e2 * bary.y;
    vec3 toLight = lightPos - position;
    float d2 = dot(toLight, toLight);
    // Zero-area triangles are not in the table; d2 = 0 means the point is on the light.
    if (!(crLen > 0.0) || !(d2 > 0.0)) return false;
    float d = sqrt(d2);
    s.direction = toLight / d;  // d > 0
    s.distance = d;
    float cosLight = dot(cr / crLen, -s.direction);  // crLen > 0
    SceneSurface surf = sceneSurface(e.light, bary);
    s.radiance = sceneEmission(surf.material, surf.uv, cosLight > 0.0);
#if SCENE_HAS_ALPHA
    s.radiance *= sceneAlphaCoverage(e.light, bary);
#endif
    // Area -> solid angle: d^2 / (area |cos|); a grazing sample has no finite pdf.
    if (!(abs(cosLight) > 0.0) || all(equal(s.radiance, vec3(0.0)))) return false;
    s.pdf = e.pdf * d2 / (area * abs(cosLight));
    return s.pdf > 0.0;
#else
    return false;
#endif
#else
    return false;
#endif
}

// Picks the environment (with sceneEnvironmentSelectProbability, decided by the coin u.y, which is
// then rescaled to [0, 1) for the chosen strategy) or a light of the alias table. Returns false
// when nothing emits or the sample carries nothing. The environment's directions reach
// kSceneInfiniteDistance; its pdf is a solid-angle pdf (MIS against BRDF rays that escape, with
// sceneEnvironmentPdf).
bool sceneSampleLight(vec3 position, vec4 u, out SceneLightSample s) {
    s.direction = vec3(0.0, 0.0, 1.0);
    s.distance = 0.0;
    s.radiance = vec3(0.0);
    s.pdf = 0.0;
    s.isDelta = false;
    s.light = 0u;
    float env = sceneEnvironmentSelectProbability();
    if (env > 0.0) {
        if (u.y < env) {
            // env > 0 here; the quotient is < 1 up to rounding: clamped below 1 like the others.
            u.y = min(u.y / env, 0.99999994);
            s.light = kSceneEnvironmentLight;
            s.distance = kSceneInfiniteDistance;
            return sceneSampleEnvironment(u, s.direction, s.radiance, s.pdf);
        }
        // u.y >= env and u.y < 1, so env < 1 here: no division by zero.
        u.y = min((u.y - env) / (1.0 - env), 0.99999994);
    }
    if (!sceneSampleTableLight(position, u, s)) return false;
    s.pdf *= 1.0 - env;
    return s.pdf > 0.0;
}

#endif
