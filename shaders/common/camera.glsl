// The frame's camera (core/scene/CameraGpu.h mirrors this block; the render graph binds it to
// every pipeline that declares it). Conventions, used by every pass:
//  - Pixel (x, y) has y = 0 at the TOP row; its centre is (x + 0.5, y + 0.5).
//  - Stereo (seed 000 §3.1): one side-by-side image; eye e covers columns
//    [e * eyeWidth, (e + 1) * eyeWidth). Eye 0 is the left eye.
//  - Motion vector of a pixel = (its position in the previous frame) - (its position now), in
//    pixels of the same eye image, jitter-free (TAA removes jitter itself).
#ifndef FOVEA_CAMERA_GLSL
#define FOVEA_CAMERA_GLSL

struct CameraEye {
    mat4 viewProj;
    mat4 prevViewProj;
    mat4 cameraToWorld;
    vec4 position;  // xyz; w = first column of the eye (float)
    vec4 gaze;      // xy in [0,1]^2 of the eye's image; zw the previous frame's (same units)
};

// Explicit binding 26, next to the scene's 16-25 (see scene_data.glsl for why not automatic).
layout(std140, binding = 26) uniform CameraInfo {
    CameraEye eyes[2];
    uvec4 size;    // x eye width, y height, z eye count, w cut
    vec4 jitter;   // xy jitter (pixels), z tan(yfov / 2), w eye aspect
    uvec4 frame;   // x frame index, y frames since reset, z model (0 perspective, 1 equirect)
} camera_info;

const float kCameraPi = 3.14159265358979;

// Equirect model (Camera.h CameraModel): the whole sphere in a 2:1 latitude-longitude image.
bool cameraIsEquirect() { return camera_info.frame.z == 1u; }

// Camera-frame direction of uv in [0,1]^2 of an equirect image: longitude (u - 0.5) 2π about +Y
// (u = 0.5 looks down -Z), latitude (0.5 - v) π. Unit length by construction.
vec3 cameraEquirectDirection(vec2 uv) {
    float longitude = (uv.x - 0.5) * 2.0 * kCameraPi, latitude = (0.5 - uv.y) * kCameraPi;
    return vec3(cos(latitude) * sin(longitude), sin(latitude), -cos(latitude) * cos(longitude));
}

// The inverse (Camera.cpp equirectUv). GLSL leaves atan(0, 0) undefined, so the poles (x = z = 0)
// take longitude 0 explicitly; the zero vector maps to the centre.
vec2 cameraEquirectUv(vec3 d) {
    float len = length(d);
    if (len <= 1e-30) return vec2(0.5);
    d /= len;  // guarded above
    float longitude = (abs(d.x) + abs(d.z) > 0.0) ? atan(d.x, -d.z) : 0.0;
    float latitude = asin(clamp(d.y, -1.0, 1.0));
    return vec2(longitude / (2.0 * kCameraPi) + 0.5, 0.5 - latitude / kCameraPi);
}

uint cameraEyeCount() { return camera_info.size.z; }
uvec2 cameraEyeSize() { return camera_info.size.xy; }
uvec2 cameraImageSize() { return uvec2(camera_info.size.x * camera_info.size.z, camera_info.size.y); }

// The eye a pixel of the side-by-side image belongs to; eyeWidth >= 1 (Camera.cpp clamps it).
uint cameraEyeOf(uint x) { return min(x / max(camera_info.size.x, 1u), camera_info.size.z - 1u); }

// A primary ray through `pixel` (image coordinates of the whole side-by-side image, e.g.
// pixel + 0.5 + jitter). Built from the camera basis rather than by unprojecting the far plane,
// so precision does not depend on the near/far planes or the distance to the origin.
void cameraRay(uint eye, vec2 pixel, out vec3 origin, out vec3 direction) {
    CameraEye e = camera_info.eyes[eye];
    vec2 local = pixel - vec2(e.position.w, 0.0);
    vec2 size = vec2(camera_info.size.xy);  // >= 1 each
    origin = e.position.xyz;
    if (cameraIsEquirect()) {
        direction = normalize(mat3(e.cameraToWorld) * cameraEquirectDirection(local / size));
        return;  // a rotation of a unit vector: the normalize only removes rounding
    }
    vec2 ndc = vec2(2.0 * local.x / size.x - 1.0, 1.0 - 2.0 * local.y / size.y);
    float t = camera_info.jitter.z;
    vec3 d = vec3(ndc.x * t * camera_info.jitter.w, ndc.y * t, -1.0);
    direction = normalize(mat3(e.cameraToWorld) * d);  // |d| >= 1 (z = -1)
}

// Where world point `p` was in the previous frame, in pixels of the side-by-side image. Returns
// false when it was behind the previous camera (no valid reprojection).
bool cameraPreviousPixel(uint eye, vec3 p, out vec2 pixel) {
    CameraEye e = camera_info.eyes[eye];
    vec4 clip = e.prevViewProj * vec4(p, 1.0);
    if (cameraIsEquirect()) {  // prevViewProj is the previous view matrix: clip.xyz is view space
        if (dot(clip.xyz, clip.xyz) <= 1e-20) { pixel = vec2(-1.0); return false; }
        pixel = cameraEquirectUv(clip.xyz) * vec2(camera_info.size.xy) + vec2(e.position.w, 0.0);
        return true;
    }
    if (clip.w <= 1e-6) { pixel = vec2(-1.0); return false; }  // guards the division below
    vec2 ndc = clip.xy / clip.w;
    vec2 size = vec2(camera_info.size.xy);
    pixel = vec2((ndc.x * 0.5 + 0.5) * size.x + e.position.w, (0.5 - ndc.y * 0.5) * size.y);
    return true;
}

// Linear view depth of `p` (distance along the eye's viewing axis, positive in front); for the
// equirect model, which has no single axis, the distance from the eye.
float cameraViewDepth(uint eye, vec3 p) {
    CameraEye e = camera_info.eyes[eye];
    if (cameraIsEquirect()) return length(p - e.position.xyz);
    return dot(p - e.position.xyz, -e.cameraToWorld[2].xyz);
}

#endif
