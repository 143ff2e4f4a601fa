// Colour helpers shared by passes.
#ifndef FOVEA_COLOR_GLSL
#define FOVEA_COLOR_GLSL

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }  // Rec. 709

// IEC 61966-2-1 sRGB transfer; input clamped to [0,1] so pow never sees a negative base.
vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// albedo' of demodulation (PathTrace: demodulated = (radiance - emission) / albedo'): the albedo
// per channel where it is > 1e-3 and finite, else 1, so a near-black, NaN or Inf albedo is
// neither divided by nor multiplied with. Used where a remodulated colour is taken apart again
// (BMFR phase III, HistoryFix).
vec3 demodulationAlbedo(vec3 a) {
    vec3 r = vec3(1.0);
    for (int c = 0; c < 3; ++c) r[c] = a[c] > 1e-3 && !isinf(a[c]) ? a[c] : 1.0;
    return r;
}

// Replaces NaN/Inf by zero so they never enter history buffers or outputs.
vec4 sanitize(vec4 c) {
    return vec4(isnan(c.x) || isinf(c.x) ? 0.0 : c.x, isnan(c.y) || isinf(c.y) ? 0.0 : c.y,
                isnan(c.z) || isinf(c.z) ? 0.0 : c.z, isnan(c.w) || isinf(c.w) ? 0.0 : c.w);
}

#endif
