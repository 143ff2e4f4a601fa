#version 460
// Unwarp step 3 (seed 003 P5 §3.5): the foveated Gaussian blur in two separable passes. sigma is
// 0 inside the fovea (the pixel is copied bit for bit) and rises linearly with the eccentricity
// (degrees, from the camera's field of view) from the fovea's edge to sigmaMax at blurDegrees,
// clamped beyond (ours; P5 stops at 30 degrees); unwarp_lookup.comp computes it once per pixel.
// Taps never cross the eye seam; the weights are renormalized at image edges. sigma is a per-pixel
// function, so the two passes only approximate a 2D Gaussian where sigma varies.
#extension GL_GOOGLE_include_directive : require

#include "../common/camera.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// One pipeline per direction (UnwarpPass compiles both): each reads and writes one image, with no
// run-time choice of image per tap (llvmpipe would evaluate a select's two loads).
#ifdef FOVEATED_BLUR_VERTICAL
layout(rgba32f) uniform readonly image2D blur_tmp;
layout(rgba32f) uniform writeonly image2D result;
#define SOURCE blur_tmp
#define TARGET result
const ivec2 kAxis = ivec2(0, 1);
#else
layout(rgba32f) uniform readonly image2D unwarped;
layout(rgba32f) uniform writeonly image2D blur_tmp;
#define SOURCE unwarped
#define TARGET blur_tmp
const ivec2 kAxis = ivec2(1, 0);
#endif
layout(rgba32f) uniform readonly image2D lookup;  // w: sigma per pixel (unwarp_lookup.comp)

const int kMaxRadius = 64;

vec4 load(ivec2 p) { return imageLoad(SOURCE, p); }

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(cameraImageSize());
    if (p.x >= size.x || p.y >= size.y) return;
    uint eye = cameraEyeOf(uint(p.x));
    int eyeX = int(eye * cameraEyeSize().x);
    float s = imageLoad(lookup, p).w;
    vec4 c = load(p);
    if (s > 0.0) {
        int radius = min(int(ceil(3.0 * s)), kMaxRadius);
        const ivec2 axis = kAxis;
        ivec2 lo = ivec2(eyeX, 0), hi = ivec2(eyeX + int(cameraEyeSize().x) - 1, size.y - 1);
        // Weights exp(k o^2) by the recurrence w(o) = w(o - 1) g(o), g(o) = g(o - 1) e^(2k),
        // g(1) = e^k: two exp per pixel instead of one per tap (all factors in (0, 1]).
        vec4 sum = c;
        float wsum = 1.0;
        float k = -0.5 / (s * s);  // s > 0
        float w = 1.0, g = exp(k), g2 = exp(2.0 * k);
        for (int o = 1; o <= radius; ++o) {
            w *= g;
            g *= g2;
            ivec2 qa = p - axis * o, qb = p + axis * o;
            if (all(greaterThanEqual(qa, lo))) { sum += w * load(qa); wsum += w; }
            if (all(lessThanEqual(qb, hi))) { sum += w * load(qb); wsum += w; }
        }
        c = sum / wsum;  // the centre tap (w = 1) is always counted: wsum >= 1
    }
    imageStore(TARGET, p, c);
}
