#version 460
// PreviewSamples, step 2: one thread per sample of the frame's budget draws a direction on the
// sphere (camera frame) by the method of seed 003 P4 §4.1 and counts it in the equirect texel it
// falls into. The equirect image and its gaze live in the camera frame (camera.glsl), so no
// world-space transform is needed here.
#extension GL_GOOGLE_include_directive : require
#include "../common/camera.glsl"
#include "../common/hmd_viewport.glsl"
#include "../common/random.glsl"
#include "../common/visual_polar.glsl"
#include "counts.glsl"

layout(local_size_x = 64) in;

layout(push_constant) uniform Params {
    uvec2 size;            // equirect image, 2:1, each >= 1
    uint budget;           // samples this frame
    uint method;           // 0 omni (OD), 1 viewport (VP), 2 foveated (FV)
    uint exactInverse;     // FV: 1 = Newton-refined inverse, 0 = P4 Eq. 7 as published
    uint headFollowsGaze;  // VP: 1 = the viewport is centred on the gaze, 0 = on -Z
    float tanHalfFov;      // VP: tan(vertical FOV / 2)
    float aspect;          // VP: width / height of the HMD eye image
    uint seedLo, seedHi;
    uint frame;
} pc;

const float kDegrees = kCameraPi / 180.0;

// P4 Eq. 7 (= P3 Eq. 6 x 80): the square-root branch is exact (the acuity is flat up to 5.79°,
// where f = 0.0965), the polynomial is P5 Eq. 3's fit (visual_polar.glsl).
float acuityInversePublished(float u) {
    return u <= 0.0965 ? 18.64 * sqrt(max(u, 0.0)) : vpAcuityInversePolynomial(u);
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.budget) return;
    uint h = hashCombine(hashCombine(hashCombine(pcgHash(pc.seedLo), pc.seedHi), pc.frame), i);
    float u1 = uintToUnitFloat(hashCombine(h, 1u)), u2 = uintToUnitFloat(hashCombine(h, 2u));

    vec2 uv;
    if (pc.method == 0u) {
        uv = vec2(u1, u2);  // OD: every texel of the equirect image alike
    } else {
        vec3 gaze = cameraEquirectDirection(camera_info.eyes[0].gaze.xy);  // unit
        vec3 d;
        if (pc.method == 1u) {
            // VP: a uniform point of the viewport's image plane, through the HMD's pinhole.
            vec3 head = pc.headFollowsGaze != 0u ? gaze : vec3(0.0, 0.0, -1.0);
            d = hmdViewportDirection(head, 2.0 * vec2(u1, u2) - 1.0, pc.tanHalfFov, pc.aspect);
        } else {
            // FV (P4 Eq. 2-7): eccentricity e by the inversion method, angle uniform.
            float e = pc.exactInverse != 0u ? vpAcuityInverse(u1) : acuityInversePublished(u1);
            float phi = 2.0 * kCameraPi * u2;
            vec3 t, b;
            hmdBasis(gaze, t, b);
            float er = e * kDegrees;
            d = cos(er) * gaze + sin(er) * (cos(phi) * t + sin(phi) * b);
        }
        uv = cameraEquirectUv(d);  // |d| > 0: VP's head term dominates, FV's d is unit
    }
    uvec2 texel = min(uvec2(uv * vec2(pc.size)), pc.size - 1u);
    atomicAdd(counts.texels[texel.y * pc.size.x + texel.x], 1u);
}
