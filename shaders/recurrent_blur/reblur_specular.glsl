// The specular half of ReBLUR (seed 004, "Cooking specular denoiser"; issue 26): the formulas
// RecurrentBlur{signal: specular} and its tests share (tests/graph/RecurrentBlurSpecularOracleTests.cpp
// checks each against a double-precision CPU version on a grid). Roughness is linear (glTF
// roughness), m = roughness^2 (seed 004 "Definitions"). Directions are world-space unit vectors;
// V points from the surface to the eye.
#ifndef FOVEA_REBLUR_SPECULAR_GLSL
#define FOVEA_REBLUR_SPECULAR_GLSL

const float kReblurPi = 3.14159265358979;

// Seed 004 "GGX dominant direction" (after Frostbite's course notes [5]): the lobe's dominant
// direction moves from the reflection vector (mirror) to the normal (roughness 1).
vec3 reblurSpecularDominantDirection(vec3 n, vec3 v, float roughness) {
    float r = clamp(roughness, 0.0, 1.0);
    float f = (1.0 - r) * (sqrt(1.0 - r) + r);  // 1 - r >= 0
    vec3 d = mix(n, reflect(-v, n), f);
    float l = length(d);
    return l > 1e-6 ? d / l : n;  // n and R on one side of the surface: d = 0 only if v = -n
}

// Seed 004 "Sample weight - normal": the lobe's half angle 90 deg * m / (1 + m) in radians
// (45 deg at roughness 1, 12 deg at 0.4 as on the slide).
float reblurSpecularLobeHalfAngle(float roughness) {
    float m = roughness * roughness;
    return 0.5 * kReblurPi * m / (1.0 + m);  // 1 + m >= 1
}

// Seed 004 "Specular accumulation using surface motion", GetMaxAllowedAccumulatedFrameNum: the
// frame count a pixel may reach, maxFrames * roughness^power with power growing with the
// parallax (angle between the previous and current view vectors) and with grazing angles:
//   a = saturate(1 - NoV)^curve, b = 1.001 + roughness^2, sensitivity = (b + a) / (b - a),
//   power = basePower * (1 + parallax * sensitivity).
// b - a >= 0.001 because a <= 1. Roughness 1 gives maxFrames at any parallax (the diffuse
// rule); roughness 0 gives 0 (a mirror accumulates nothing through surface motion). basePower 0
// turns the cap off: accumulation by surface motion alone (the talk's "naive accumulation").
float reblurMaxAccumulatedFrames(float roughness, float nov, float parallax, float maxFrames,
                                 float basePower, float curve) {
    float r = clamp(roughness, 0.0, 1.0);
    float a = pow(clamp(1.0 - nov, 0.0, 1.0), curve);
    float b = 1.001 + r * r;
    float sensitivity = (b + a) / (b - a);
    float power = basePower * (1.0 + max(parallax, 0.0) * sensitivity);
    if (!(power > 0.0)) return maxFrames;  // pow(0, 0) is undefined in GLSL
    return maxFrames * pow(r, power);  // pow(0, power > 0) = 0
}

// Seed 004 "Using hit distance to control blur radius": blurRadius *= lerp(K roughness, 1, f),
// f = hitDist / (hitDist + d), d = distance from the eye to the pixel: a reflected world close to
// the surface gives a sharp reflection, so a small radius. hitDist + d > 0 for d > 0.
float reblurHitDistanceRadiusFactor(float hitDist, float viewDistance, float roughness, float k) {
    float denominator = max(hitDist, 0.0) + viewDistance;
    float f = denominator > 0.0 ? max(hitDist, 0.0) / denominator : 1.0;
    return mix(k * roughness, 1.0, f);
}

// How much of the diffuse-sized radius a lobe of this roughness may use: 0 for a mirror (no
// spatial blur), ~1 from roughness 0.3 up. NRD's GetSpecMagicCurve (1 - 2^(-200 r^2)) r^(1/4);
// the talk itself only shrinks the normal weight's angle with roughness, which leaves a flat
// mirror blurred by the full radius.
float reblurSpecularRadiusScale(float roughness) {
    float r = clamp(roughness, 0.0, 1.0);
    return (1.0 - exp2(-200.0 * r * r)) * pow(r, 0.25);
}

// Seed 004 "Sample weight - roughness", GetRoughnessWeight: ignores samples whose roughness
// differs from the centre's by more than roughness0^2 * 0.99 + 0.01 (>= 0.01).
float reblurRoughnessWeight(float roughness0, float roughness) {
    float norm = roughness0 * roughness0 * 0.99 + 0.01;
    return clamp(1.0 - abs(roughness0 - roughness) / norm, 0.0, 1.0);
}

// Seed 004 "Sample weight - normal", GetNormalWeight: linearStep(a0, 0, angle) with a0 the lobe
// half angle times `shrink` (the talk's CloseToZeroIfAccumulationGoesWell, 1 at no history; the
// pre-blur loosens it to 2) plus 0.5 deg, so the kernel narrows as the pixel converges.
// a0 >= 0.5 deg > 0.
float reblurSpecularNormalWeight(vec3 n0, vec3 n, float roughness, float shrink) {
    float a0 = reblurSpecularLobeHalfAngle(roughness) * max(shrink, 0.0) + radians(0.5);
    float a = acos(clamp(dot(n0, n), -1.0, 1.0));
    return clamp(1.0 - a / a0, 0.0, 1.0);
}

// Seed 004 "Unifying diffuse and specular sampling" + "Anisotropic sampling", GetKernelBasis:
// the kernel lies in the plane perpendicular to the reflected dominant direction R = reflect(-D,
// n) (the tangent plane at roughness 1, the screen plane for a mirror), T = cross(n, R) (any
// tangent when n and R coincide: the slide's "doesn't handle N = R"), B = cross(R, T), both
// scaled by worldRadius; T is scaled by lerp(1, skew, normalizedFrames) <= 1, skew = lerp(1,
// roughness, angle / 90 deg) with angle = acos(|n.v|) (the slide's view-space N.z): at grazing
// angles a converged glossy kernel narrows across the reflection's streak and keeps its length
// along it (B), where isotropic taps would smear a stretched highlight sideways.
void reblurKernelBasis(vec3 n, vec3 v, float roughness, float worldRadius, float normalizedFrames,
                       out vec3 t, out vec3 b) {
    vec3 d = reblurSpecularDominantDirection(n, v, roughness);
    vec3 r = reflect(-d, n);
    vec3 c = cross(n, r);
    float cl = length(c);
    if (cl > 1e-4) {
        t = c / cl;
    } else {
        // n ~ R: any unit tangent (Duff et al. 2017 basis), as for a diffuse kernel.
        float s = n.z >= 0.0 ? 1.0 : -1.0;
        float a = -1.0 / (s + n.z);  // |s + n.z| >= 1
        t = vec3(1.0 + s * n.x * n.x * a, s * n.x * n.y * a, -s * n.x);
    }
    b = cross(r, t);
    float angle = clamp(acos(clamp(abs(dot(n, v)), 0.0, 1.0)) / (0.5 * kReblurPi), 0.0, 1.0);
    float skew = mix(1.0, clamp(roughness, 0.0, 1.0), angle);
    t *= worldRadius * mix(1.0, skew, clamp(normalizedFrames, 0.0, 1.0));
    b *= worldRadius;
}

#endif
