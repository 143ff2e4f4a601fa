// The HMD viewport of seed 003 P3/P4's 360° preview, shared by PreviewSamples (the viewport
// method samples it uniformly) and HmdPreview (which displays it), so both mean the same window:
// a pinhole looking along `head` (camera frame of the equirect image, unit), with the image's up
// as close to +Y as the head allows.
#ifndef FOVEA_HMD_VIEWPORT_GLSL
#define FOVEA_HMD_VIEWPORT_GLSL

// An orthonormal right/up pair around unit `w`.
void hmdBasis(vec3 w, out vec3 right, out vec3 up) {
    vec3 a = abs(w.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(0.0, 0.0, 1.0);
    right = normalize(cross(w, a));  // |cross| >= sqrt(1 - 0.999^2) > 0.04
    up = cross(right, w);
}

// The (unnormalized, length >= 1) direction through `ndc` in [-1, 1]^2 (y up) of the viewport.
vec3 hmdViewportDirection(vec3 head, vec2 ndc, float tanHalfFov, float aspect) {
    vec3 right, up;
    hmdBasis(head, right, up);
    return head + right * (ndc.x * tanHalfFov * aspect) + up * (ndc.y * tanHalfFov);
}

#endif
