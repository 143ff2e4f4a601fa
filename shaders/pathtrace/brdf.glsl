// BRDFs of the PathTrace pass (docs/passes/PathTrace.md "BRDF").
//  - Lambert (BRDF_GGX = 0, the default): f = baseColor / pi, cosine-weighted sampling. Peres et
//    al. shade everything with it (seed 000 §3.3 and §4.1: "Lambertian material").
//  - glTF metallic-roughness (BRDF_GGX = 1): f = (1 - F) (1 - metallic) baseColor / pi
//    + D G2 F / (4 |n.wo| |n.wi|), GGX D, height-correlated Smith G2, Schlick F with
//    F0 = mix(0.04, baseColor, metallic), alpha = roughness^2. One lobe is picked per sample
//    (probability from the Fresnel/diffuse luminance at the view angle), the specular one by
//    sampling GGX visible normals (Heitz 2018); the weight f cos / pdf always uses the pdf of
//    the whole mixture (one-sample MIS), so the choice affects variance only, never the mean.
//  - Optional bump shadowing (PathTrace bumpShadowing): the diffuse lobe times Chiang, Li and
//    Burley's shadowing term for bent shading normals (brdfBumpShadowing below), as Cycles does.
// All directions are world-space unit vectors; `n` is the shading normal on the side of wo.
#ifndef FOVEA_PATHTRACE_BRDF_GLSL
#define FOVEA_PATHTRACE_BRDF_GLSL

#ifndef BRDF_GGX
#define BRDF_GGX 0
#endif

const float kPi = 3.14159265358979;
const float kMinAlpha = 2e-3;  // below this D(h) exceeds 1e5: a float-safe near-mirror
const float kMinCos = 1e-4;    // floor of n.wo so the specular terms never divide by 0

struct BrdfInput {
    vec3 baseColor;
    float metallic;
    float roughness;
};

// Orthonormal basis around unit n (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited"): branch-free; 1 / (sign + n.z) cannot divide by 0 because |sign + n.z| >= 1.
void brdfBasis(vec3 n, out vec3 t, out vec3 b) {
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

// Cosine-weighted direction around n: pdf = cos / pi.
vec3 brdfSampleCosine(vec3 n, vec2 u) {
    float r = sqrt(u.x);  // u.x >= 0
    float phi = 2.0 * kPi * u.y;
    vec3 t, b;
    brdfBasis(n, t, b);
    float z = sqrt(max(0.0, 1.0 - u.x));
    return normalize(t * (r * cos(phi)) + b * (r * sin(phi)) + n * z);  // length ~1, never 0
}

#if BRDF_GGX
float brdfLuminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

vec3 brdfF0(BrdfInput m) { return mix(vec3(0.04), m.baseColor, m.metallic); }
vec3 brdfSchlick(vec3 f0, float cosTheta) {
    float k = 1.0 - clamp(cosTheta, 0.0, 1.0);
    return f0 + (1.0 - f0) * (k * k * k * k * k);
}
float brdfAlpha(BrdfInput m) { return max(m.roughness * m.roughness, kMinAlpha); }

// GGX normal distribution; the denominator is >= pi * a2 * min(1, a2)^2 > 0 since a >= kMinAlpha.
float brdfD(float nh, float a) {
    float a2 = a * a;
    float d = nh * nh * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}
// Smith Lambda for GGX; c = cos to the normal, > 0 (callers clamp).
float brdfLambda(float c, float a) {
    float c2 = c * c;
    float t2 = max(0.0, 1.0 - c2) / c2;  // c >= kMinCos
    return 0.5 * (sqrt(1.0 + a * a * t2) - 1.0);
}

// Probability of sampling the specular lobe. Both lobes keep >= 10% unless one is black.
float brdfSpecularProbability(BrdfInput m, float nv) {
    float ws = brdfLuminance(brdfSchlick(brdfF0(m), nv));
    float wd = brdfLuminance(m.baseColor) * (1.0 - m.metallic);
    if (!(ws + wd > 0.0)) return 0.5;
    float p = ws / (ws + wd);  // ws + wd > 0 here
    return (ws > 0.0 && wd > 0.0) ? clamp(p, 0.1, 0.9) : p;
}
#endif

// Chiang, Li & Burley 2019, "Taming the Shadow Terminator" (SIGGRAPH talk), the term Cycles
// multiplies its diffuse closures by where a normal map or bump bends the shading normal n away
// from the interpolated normal nSmooth: g = (nSmooth.wi) / ((n.wi)(nSmooth.n)), G = 1 for
// g >= 1, else -g^3 + g^2 + g (C1 at g = 1). It darkens light arriving at grazing angles to the
// interpolated surface that a bent normal would otherwise catch at full strength. 1 when n =
// nSmooth (g = 1).
float brdfBumpShadowing(vec3 nSmooth, vec3 n, vec3 wi) {
    float d = dot(n, wi) * dot(nSmooth, n);
    if (!(d > 0.0)) return 0.0;  // wi below n (f is 0 there) or n bent past 90 degrees
    float g = dot(nSmooth, wi) / d;  // d > 0
    if (g >= 1.0) return 1.0;
    if (g <= 0.0) return 0.0;
    return g * (1.0 + g * (1.0 - g));
}

// f(wo, wi) (without the cosine) split into its two lobes, the diffuse one times diffuseScale
// (bump shadowing; 1 = the plain BRDF); zero below the surface. Lambert: all of it is diffuse.
// The split feeds PathTrace's `diffuse` / `specular` signals (issue 26, seed 004).
void brdfEvalLobes(BrdfInput m, vec3 n, vec3 wo, vec3 wi, float diffuseScale, out vec3 diffuse,
                   out vec3 specular) {
    diffuse = vec3(0.0);
    specular = vec3(0.0);
    float nl = dot(n, wi);
    if (nl <= 0.0) return;
#if BRDF_GGX
    float nv = max(dot(n, wo), kMinCos);
    vec3 h = wo + wi;
    float hl = length(h);
    if (!(hl > 0.0)) return;  // wi = -wo: no half vector (cannot be above n and wo)
    h /= hl;
    float a = brdfAlpha(m);
    vec3 f = brdfSchlick(brdfF0(m), dot(h, wi));
    float g2 = 1.0 / (1.0 + brdfLambda(nv, a) + brdfLambda(max(nl, kMinCos), a));
    specular = f * (brdfD(max(dot(n, h), 0.0), a) * g2 / (4.0 * nv * max(nl, kMinCos)));
    diffuse = (1.0 - f) * (1.0 - m.metallic) * m.baseColor / kPi * diffuseScale;
#else
    diffuse = m.baseColor / kPi * diffuseScale;
#endif
}

// f(wo, wi) (without the cosine), both lobes, the diffuse one times diffuseScale.
vec3 brdfEvalScaled(BrdfInput m, vec3 n, vec3 wo, vec3 wi, float diffuseScale) {
    vec3 d, s;
    brdfEvalLobes(m, n, wo, wi, diffuseScale, d, s);
    return d + s;
}

vec3 brdfEval(BrdfInput m, vec3 n, vec3 wo, vec3 wi) { return brdfEvalScaled(m, n, wo, wi, 1.0); }

// Solid-angle pdf with which brdfSample produces wi.
float brdfPdf(BrdfInput m, vec3 n, vec3 wo, vec3 wi) {
    float nl = dot(n, wi);
    if (nl <= 0.0) return 0.0;
#if BRDF_GGX
    float nv = max(dot(n, wo), kMinCos);
    vec3 h = wo + wi;
    float hl = length(h);
    if (!(hl > 0.0)) return 0.0;
    h /= hl;
    float a = brdfAlpha(m);
    // Visible-normal pdf of h, times the reflection Jacobian 1 / (4 wo.h):
    // G1(wo) D(h) max(0, wo.h) / nv / (4 wo.h) = G1(wo) D(h) / (4 nv).
    float g1 = 1.0 / (1.0 + brdfLambda(nv, a));
    float pSpec = dot(wo, h) > 0.0 ? g1 * brdfD(max(dot(n, h), 0.0), a) / (4.0 * nv) : 0.0;
    float ps = brdfSpecularProbability(m, nv);
    return ps * pSpec + (1.0 - ps) * nl / kPi;
#else
    return nl / kPi;
#endif
}

// Samples wi; returns false when no direction above the surface was produced. u.x picks the
// lobe (GGX only; `specularLobe` says which), u.yz the direction.
bool brdfSampleLobe(BrdfInput m, vec3 n, vec3 wo, vec3 u, out vec3 wi, out bool specularLobe) {
    specularLobe = false;
#if BRDF_GGX
    float nv = max(dot(n, wo), kMinCos);
    if (u.x < brdfSpecularProbability(m, nv)) {
        specularLobe = true;
        // Heitz 2018, "Sampling the GGX Distribution of Visible Normals", in the frame of n.
        vec3 t, b;
        brdfBasis(n, t, b);
        float a = brdfAlpha(m);
        vec3 v = vec3(dot(wo, t), dot(wo, b), max(dot(wo, n), kMinCos));
        vec3 vh = normalize(vec3(a * v.x, a * v.y, v.z));  // z > 0: never zero length
        float lensq = vh.x * vh.x + vh.y * vh.y;
        vec3 t1 = lensq > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(lensq) : vec3(1.0, 0.0, 0.0);
        vec3 t2 = cross(vh, t1);
        float r = sqrt(u.y);
        float phi = 2.0 * kPi * u.z;
        float p1 = r * cos(phi);
        float p2 = r * sin(phi);
        float s = 0.5 * (1.0 + vh.z);
        p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * p2;
        vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
        vec3 hLocal = normalize(vec3(a * nh.x, a * nh.y, max(0.0, nh.z)));  // nh.z ~ 1 >= ...
        vec3 h = t * hLocal.x + b * hLocal.y + n * hLocal.z;
        wi = reflect(-wo, h);
        return dot(n, wi) > 0.0;
    }
#endif
    wi = brdfSampleCosine(n, u.yz);
    return dot(n, wi) > 0.0;
}

bool brdfSample(BrdfInput m, vec3 n, vec3 wo, vec3 u, out vec3 wi) {
    bool specularLobe;
    return brdfSampleLobe(m, n, wo, u, wi, specularLobe);
}

// f cos / pdf for a direction from brdfSample (0 when the pdf vanishes) split by lobe, the
// diffuse lobe times diffuseScale as in brdfEvalLobes. The pdf is the mixture's, so both parts
// are unbiased whichever lobe produced wi.
void brdfWeightLobes(BrdfInput m, vec3 n, vec3 wo, vec3 wi, float diffuseScale, out vec3 diffuse,
                     out vec3 specular) {
#if BRDF_GGX
    diffuse = vec3(0.0);
    specular = vec3(0.0);
    float pdf = brdfPdf(m, n, wo, wi);
    if (!(pdf > 0.0)) return;
    brdfEvalLobes(m, n, wo, wi, diffuseScale, diffuse, specular);
    float k = dot(n, wi) / pdf;  // pdf > 0 here
    diffuse *= k;
    specular *= k;
#else
    diffuse = m.baseColor * diffuseScale;  // (rho / pi) cos / (cos / pi)
    specular = vec3(0.0);
#endif
}

vec3 brdfWeightScaled(BrdfInput m, vec3 n, vec3 wo, vec3 wi, float diffuseScale) {
    vec3 d, s;
    brdfWeightLobes(m, n, wo, wi, diffuseScale, d, s);
    return d + s;
}

#endif
