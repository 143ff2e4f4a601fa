#version 460
// RecurrentBlur temporal accumulation (seed 004, the ReBLUR talk; specs §2 "Stage temporal"):
// reproject the recurrent history (last frame's post-blurred output, a delay-1 edge from the
// spatial node) with a 2x2 bilinear footprint whose taps are kept only when the previous surface
// lies on the current pixel's plane (talk: "cut off if relative delta >= 0.5-1.5 %" of the
// frustum size); the custom weights are bilinear x valid, renormalized over the valid taps
// (talk: GetBilinearCustomWeights). The frame count N is the same weighted average of the taps'
// counts plus one (never the max: a max would let one stale tap keep a disoccluded pixel's
// history long), capped at maxFrames; the blend weight of the new frame is 1/(1+N), the talk's
// "linear accumulation speed" (proof slide: a running mean up to the cap, then an EMA).
// A firefly suppressor limits the new sample's luminance relative to the history's.
// Ours: a tap is also dropped when its normal deviates from the pixel's (cos < cosNormal, as
// BMFR's normal test): the plane distance alone accepts a floor or wall point lying in the plane
// of a box's side face, so a face revealed by the camera inherited the floor's colour (issue 13,
// error by history age on the glTF Cornell box).
// REBLUR_SPECULAR (signal = specular, seed 004 "Specular accumulation using surface motion"):
// the history is still found through the surface motion, but the frame count is capped by
// reblurMaxAccumulatedFrames(roughness, NoV, parallax): "we don't touch MVs, we adapt the
// accumulation speed". Parallax = |previous eye - eye| / distance to the point x frame rate (the
// talk's length(movementDelta) / (distToPoint * frameTime)).
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

uniform sampler2D preblurred;  // this frame's pre-blurred radiance, a = h (normalized hit)
uniform sampler2D history;     // last frame's post-blurred result, a = h (delay-1 edge)
uniform sampler2D prev_geo;    // our own geometry of last frame: xyz position, w = N (-1 miss)
uniform sampler2D prev_geonormal;  // last frame's shading normal (0 = no surface)
uniform sampler2D normal;
uniform sampler2D position;
uniform sampler2D depth;
uniform sampler2D motion;
#if REBLUR_SPECULAR  // declared only where used: an unused sampler would sit at binding 0
uniform sampler2D roughness;  // GBuffer roughness_metallic (r = linear roughness)
#endif
layout(rgba32f) uniform writeonly image2D accumulated;  // rgb accumulated, a = N
layout(r32f) uniform writeonly image2D hit;             // accumulated normalized hit distance
layout(rgba32f) uniform writeonly image2D geo;          // xyz position, w = N (-1: no surface)
layout(rgba16f) uniform writeonly image2D geonormal;    // unit normal (0: no surface)

layout(push_constant) uniform Params {
    ivec2 size;
    int eyeWidth;
    int eyes;
    float tanHalfFov;
    int useHistory;      // 0: first frame, reset, camera cut (history invalid)
    int useMotion;       // 0: no motion input (still camera)
    float maxFrames;     // cap of N (talk: "< 32"; NRD 30)
    float threshold;     // disocclusion: plane distance as a fraction of the frustum size
    int firefly;         // 1: firefly suppression on
    float maxBlurRadius; // strength of the firefly suppressor grows with it (specs §2)
    float cosNormal;     // disocclusion: minimum cosine between the tap's normal and ours; -1 off
    // Specular: the previous frame's eye positions (w = 1 when known; this frame's are
    // camera_info's).
    vec4 prevEyePosition0;
    vec4 prevEyePosition1;
    float frameRate;     // 1 / the talk's frameTime
    float accumBasePower;  // SPEC_ACCUM_BASE_POWER
    float accumCurve;      // SPEC_ACCUM_CURVE
    int virtualMotion;     // 1: also reproject the reflected image (specular)
} pc;

vec3 unitNormal(vec4 n) {
    float l = length(n.xyz);
    return l > 1e-8 && !isnan(l) && !isinf(l) ? n.xyz / l : vec3(0.0, 0.0, 1.0);
}

// The recurrent history at previous-frame position f (pixel centre minus 0.5): the 2x2 bilinear
// footprint, each tap kept only when the previous surface lies on this pixel's plane and (unless
// off: cosNormal -1) has a normal within acos(cosNormal); h = the renormalized average, n = the
// taps' count + 1, capped. False when no tap survives.
bool reprojectHistory(vec2 f, vec3 x, vec3 nrm, float frustum, float cosNormal, ivec2 lo,
                      ivec2 hi, out vec4 h, out float n) {
    h = vec4(0.0);
    n = 0.0;
    ivec2 i0 = ivec2(floor(clamp(f, vec2(-1e6), vec2(1e6))));
    vec2 t = f - vec2(i0);
    vec4 sum = vec4(0.0);
    float nsum = 0.0, wsum = 0.0;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 q = i0 + o;
        // In the same eye (never across the seam) and on screen.
        if (any(lessThan(q, lo)) || any(greaterThan(q, hi))) continue;
        float wb = (o.x == 1 ? t.x : 1.0 - t.x) * (o.y == 1 ? t.y : 1.0 - t.y);
        vec4 g = texelFetch(prev_geo, q, 0);
        if (!(g.w >= 0.0)) continue;  // no surface there last frame (or NaN)
        // Plane distance of the previous surface to this pixel's plane.
        if (!(abs(dot(nrm, g.xyz - x)) <= pc.threshold * frustum)) continue;
        // Normal test (ours): a zero normal (no surface) or NaN fails it unless it is off.
        if (cosNormal > -1.0 && !(dot(nrm, texelFetch(prev_geonormal, q, 0).xyz) >= cosNormal))
            continue;
        float w = wb;
        if (!(w > 0.0)) continue;
        sum += w * sanitize(texelFetch(history, q, 0));
        nsum += w * min(g.w, pc.maxFrames);
        wsum += w;
    }
    if (!(wsum > 1e-6)) return false;  // a footprint that barely touches a valid tap
    h = sum / wsum;
    n = min(nsum / wsum + 1.0, pc.maxFrames);
    return true;
}

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    ivec2 lo, hi;
    eyeBounds(p, pc.size, pc.eyeWidth, pc.eyes, lo, hi);

    vec4 c = sanitize(texelFetch(preblurred, p, 0));  // finite already; cheap insurance
    float z = texelFetch(depth, p, 0).r;
    vec3 x = texelFetch(position, p, 0).xyz;
    if (!(z > 0.0) || any(isnan(x)) || any(isinf(x))) {
        // No surface: nothing to accumulate; every output is still written.
        imageStore(accumulated, p, vec4(c.rgb, 0.0));
        imageStore(hit, p, vec4(1.0));
        imageStore(geo, p, vec4(0.0, 0.0, 0.0, -1.0));
        imageStore(geonormal, p, vec4(0.0));
        return;
    }
    vec3 nrm = unitNormal(texelFetch(normal, p, 0));
    float frustum = frustumSize(pc.tanHalfFov, z);  // > 0

    float n = 0.0;
    vec4 h = c;  // no history: the frame alone
    if (pc.useHistory != 0) {
        vec2 mv = pc.useMotion != 0 ? texelFetch(motion, p, 0).xy : vec2(0.0);
        if (any(isnan(mv)) || any(isinf(mv))) mv = vec2(1e9);  // off-screen: no history
        // Previous position of the pixel centre, minus 0.5.
        bool surface = reprojectHistory(vec2(p) + mv, x, nrm, frustum, pc.cosNormal, lo, hi, h, n);
#if REBLUR_SPECULAR
        uint eye = uint(min(p.x / pc.eyeWidth, pc.eyes - 1));
        vec4 e = vec4(camera_info.eyes[eye].position.xyz, 1.0);
        vec4 ePrev = eye == 0u ? pc.prevEyePosition0 : pc.prevEyePosition1;
        vec3 toEye = e.xyz - x;
        float dist = length(toEye);
        float parallax = ePrev.w > 0.0 && dist > 0.0
                             ? length(e.xyz - ePrev.xyz) / dist * pc.frameRate  // dist > 0
                             : 0.0;
        float nov = dist > 0.0 ? abs(dot(nrm, toEye / dist)) : 1.0;
        float r = clamp(sanitize(texelFetch(roughness, p, 0)).r, 0.0, 1.0);
        // Surface-motion history: capped by GetMaxAllowedAccumulatedFrameNum.
        if (surface)
            n = min(n, reblurMaxAccumulatedFrames(r, nov, parallax, pc.maxFrames,
                                                  pc.accumBasePower, pc.accumCurve));
        // Virtual motion (ours after NRD; the talk reprojects by surface motion only): the
        // reflected image of a planar mirror lies hitDist behind the surface along the view
        // ray; where it was last frame is where its history is. Weighted by how mirror-like
        // the lobe is (the dominant direction's factor f: 1 mirror, 0 at roughness 1). The
        // planar-mirror assumption holds where the surface is flat: a virtual tap must have the
        // pixel's normal within the lobe's half angle + 2 deg (a curved mirror, whose reflection
        // moves otherwise, falls back to the surface history).
        if (pc.virtualMotion != 0 && dist > 0.0) {
            float hitDist = denormalizeHitDistance(c.a, hitDistanceScale(pc.tanHalfFov, z, r));
            vec3 xv = x - toEye / dist * hitDist;  // dist > 0
            vec2 pv;
            vec4 hv;
            float nv;
            float cosVirtual =
                max(pc.cosNormal, cos(min(reblurSpecularLobeHalfAngle(r) + radians(2.0), 1.5)));
            if (cameraPreviousPixel(eye, xv, pv) &&
                reprojectHistory(pv - 0.5, x, nrm, frustum, cosVirtual, lo, hi, hv, nv)) {
                float f = (1.0 - r) * (sqrt(1.0 - r) + r);  // 1 - r >= 0
                float amount = surface ? f : 1.0;
                h = mix(h, hv, amount);
                n = mix(n, nv, amount);
                surface = true;
            }
        }
#endif
        if (!surface) {  // no usable history: the frame alone
            h = c;
            n = 0.0;
        }
    }
    float a = 1.0 / (1.0 + n);  // the talk's linear accumulation speed

    vec3 cur = c.rgb;
    if (pc.firefly != 0 && n > 0.0) {
        // Firefly suppressor (specs §2): the new sample's luminance may exceed the history's by
        // at most maxRel, applied with strength f = k / (1 + k), k = 0.1 N maxBlurRadius.
        float y = luminance(cur), yh = max(luminance(h.rgb), 0.0);
        float maxRel = 2.0 + 38.0 / (n + 1.0);
        float k = 0.1 * n * pc.maxBlurRadius;
        float fs = k / (1.0 + k);
        float y2 = mix(y, min(y, yh * maxRel), fs);
        if (y > 1e-20) cur *= y2 / y;  // guard: a black sample stays black
    }
    vec3 acc = mix(h.rgb, cur, a);
    float hacc = clamp(mix(h.a, c.a, a), 0.0, 1.0);
    imageStore(accumulated, p, sanitize(vec4(acc, n)));
    imageStore(hit, p, vec4(hacc));
    imageStore(geo, p, vec4(x, n));
    imageStore(geonormal, p, vec4(nrm, 0.0));
}
