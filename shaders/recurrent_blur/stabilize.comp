#version 460
// RecurrentBlur temporal stabilization of luminance (seed 004: the diffuse pipeline ends with
// "temporal stabilization"; specs §2 "TS"): the post-blurred colour's luminance is blended with
// its own stabilized luminance of last frame (reprojected), clamped to the 3x3 neighbourhood's
// mean +- sigma band; antilag: a history far outside mean +- antilagSigma sigma shortens the
// stabilization (A < 1), so a light switch is followed faster. Colour is rescaled to the
// stabilized luminance (chroma untouched).
#extension GL_GOOGLE_include_directive : require
#include "common/color.glsl"
#include "recurrent_blur/reblur_common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D history;          // this frame's post-blurred colour (a = h)
uniform sampler2D color;            // the spatial stage's input, a = N
uniform sampler2D depth;
uniform sampler2D motion;
uniform sampler2D prev_stabilized;  // own luminance history (pass-declared)
layout(rgba32f) uniform writeonly image2D result;  // rgb stabilized, a = 1
layout(r32f) uniform writeonly image2D stabilized;

layout(push_constant) uniform Params {
    ivec2 size;
    int eyeWidth;
    int eyes;
    int useHistory;
    int useMotion;
    float maxStabilized;  // max stabilized frames (0 = off): strength <= m / (1 + m)
    int antilag;
    float antilagSigma;   // sigmas of the antilag band (NRD 4)
    float antilagSensitivity;
} pc;

float lumaAt(ivec2 q, ivec2 lo, ivec2 hi) {
    return luminance(sanitize(texelFetch(history, clamp(q, lo, hi), 0)).rgb);
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    ivec2 lo, hi;
    eyeBounds(p, pc.size, pc.eyeWidth, pc.eyes, lo, hi);

    vec4 c = sanitize(texelFetch(history, p, 0));
    float n = max(sanitize(texelFetch(color, p, 0)).a, 0.0);
    float z = texelFetch(depth, p, 0).r;
    float y = luminance(c.rgb);
    float ys = y;
    if (pc.useHistory != 0 && pc.maxStabilized > 0.0 && z > 0.0 && n > 0.0) {
        float m1 = 0.0, m2 = 0.0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                float s = lumaAt(p + ivec2(dx, dy), lo, hi);
                m1 += s;
                m2 += s * s;
            }
        m1 /= 9.0;
        float sigma = sqrt(max(m2 / 9.0 - m1 * m1, 0.0));  // rounding can make it < 0
        vec2 mv = pc.useMotion != 0 ? texelFetch(motion, p, 0).xy : vec2(0.0);
        vec2 f = vec2(p) + mv;
        bool ok = !any(isnan(mv)) && !any(isinf(mv));
        ivec2 i0 = ivec2(floor(ok ? f : vec2(-1e6)));
        vec2 t = f - vec2(i0);
        float lh = 0.0, wsum = 0.0;
        for (int k = 0; k < 4 && ok; ++k) {
            ivec2 o = ivec2(k & 1, k >> 1);
            ivec2 q = i0 + o;
            if (any(lessThan(q, lo)) || any(greaterThan(q, hi))) continue;
            float w = (o.x == 1 ? t.x : 1.0 - t.x) * (o.y == 1 ? t.y : 1.0 - t.y);
            if (!(w > 0.0)) continue;
            float v = texelFetch(prev_stabilized, q, 0).r;
            lh += w * (isnan(v) || isinf(v) ? 0.0 : v);
            wsum += w;
        }
        if (wsum > 1e-6) {
            lh = max(lh / wsum, 0.0);
            float antilag = 1.0;
            if (pc.antilag != 0) {
                float hc = clamp(lh, m1 - pc.antilagSigma * sigma, m1 + pc.antilagSigma * sigma);
                float d = abs(lh - hc) / (max(lh, hc) + 1e-6);  // relative, in [0, 1]
                antilag = 1.0 / (1.0 + d * n * pc.antilagSensitivity);
            }
            float w = n / (1.0 + n) * antilag;
            lh = clamp(lh, m1 - sigma * (1.0 + 3.0 * w), m1 + sigma * (1.0 + 3.0 * w));
            ys = mix(y, lh, min(w, pc.maxStabilized / (1.0 + pc.maxStabilized)));
        }
    }
    vec3 rgb = y > 1e-20 ? c.rgb * (ys / y) : c.rgb;  // guard: black stays black
    imageStore(result, p, sanitize(vec4(rgb, 1.0)));  // a = 1: the image is final (N: color.a)
    float yOut = luminance(rgb);
    imageStore(stabilized, p, vec4(isnan(yOut) || isinf(yOut) ? 0.0 : max(yOut, 0.0)));
}
