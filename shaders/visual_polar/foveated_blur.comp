#version 460
// Unwarp step 3 (seed 003 P5 §3.5): the foveated Gaussian blur in two separable passes. sigma is
// 0 inside the fovea (the pixel is copied bit for bit) and rises linearly with the eccentricity
// (degrees, from the camera's field of view) from the fovea's edge to sigmaMax at blurDegrees,
// clamped beyond (ours; P5 stops at 30 degrees). Taps never cross the eye seam; the weights are
// renormalized at image edges. sigma is a per-pixel function, so the two passes only
// approximate a 2D Gaussian where sigma varies.
#extension GL_GOOGLE_include_directive : require

#include "../common/camera.glsl"
#define VISUAL_POLAR_PARAMS
#include "../common/visual_polar.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f) uniform image2D unwarped;
layout(rgba32f) uniform image2D blur_tmp;
layout(rgba32f) uniform writeonly image2D result;

layout(push_constant) uniform Params {
    float sigmaMax;     // pixels at blurDegrees for this height
    float blurDegrees;  // >= 1
    uint vertical;      // 0: unwarped -> blur_tmp (x), 1: blur_tmp -> result (y)
} pc;

const int kMaxRadius = 64;

// View-space direction through a point of an eye image (camera.glsl's cameraRay convention).
vec3 viewDirection(vec2 local) {
    vec2 size = vec2(max(cameraEyeSize(), uvec2(1u)));
    vec2 ndc = vec2(2.0 * local.x / size.x - 1.0, 1.0 - 2.0 * local.y / size.y);
    float t = camera_info.jitter.z;
    return vec3(ndc.x * t * camera_info.jitter.w, ndc.y * t, -1.0);
}

// Angle in degrees between two view directions (atan form: accurate for small angles).
float angleDegrees(vec3 a, vec3 b) { return degrees(atan(length(cross(a, b)), dot(a, b))); }

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

vec4 load(ivec2 p) { return pc.vertical == 0u ? imageLoad(unwarped, p) : imageLoad(blur_tmp, p); }

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(cameraImageSize());
    if (p.x >= size.x || p.y >= size.y) return;
    uint eyes = clamp(vp.grid.z, 1u, 2u);
    uint eye = min(cameraEyeOf(uint(p.x)), eyes - 1u);
    int eyeX = int(eye * cameraEyeSize().x);
    VisualPolarMap m = vpMapOfEye(eye);
    float sigma = sigmaAt(m, vec2(p) + 0.5 - vec2(float(eyeX), 0.0));
    vec4 c = load(p);
    if (sigma > 0.0) {
        int radius = min(int(ceil(3.0 * sigma)), kMaxRadius);
        ivec2 axis = pc.vertical == 0u ? ivec2(1, 0) : ivec2(0, 1);
        ivec2 lo = ivec2(eyeX, 0), hi = ivec2(eyeX + int(cameraEyeSize().x) - 1, size.y - 1);
        vec4 sum = vec4(0.0);
        float wsum = 0.0;
        float k = -0.5 / (sigma * sigma);  // sigma > 0
        for (int o = -radius; o <= radius; ++o) {
            ivec2 q = p + axis * o;
            if (any(lessThan(q, lo)) || any(greaterThan(q, hi))) continue;
            float w = exp(k * float(o * o));
            sum += w * load(q);
            wsum += w;
        }
        c = sum / wsum;  // the centre tap (w = 1) is always inside: wsum >= 1
    }
    if (pc.vertical == 0u) imageStore(blur_tmp, p, c);
    else imageStore(result, p, c);
}
