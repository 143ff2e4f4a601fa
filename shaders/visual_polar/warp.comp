#version 460
// VisualPolarWarp (seed 003 P5 §3.2): the Visual-Polar grid of each eye around its own gaze,
// side by side; per texel the screen position of its primary ray (texel centre) and whether it
// is traced. Thread (0, 0) also writes the `vp` block for every consumer.
#extension GL_GOOGLE_include_directive : require

#include "../common/camera.glsl"
#define VISUAL_POLAR_PARAMS_WRITE
#include "../common/visual_polar.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f) uniform writeonly image2D coords;

layout(push_constant) uniform Params {
    float foveaFraction;  // rho_f, clamped by the pass to [0.1, 0.5]
    float foveaDegrees;   // f^-1(rho_f), computed on the CPU
    uint traceOffscreen;  // 1: texels off the screen are traced too
    uint stairBlock;      // P5 §3.3 staircase: block width B (0 = the triangular clip)
    uint stairOffset;     // this frame's block offset x, < B
    uint stairPrevOffset; // the previous frame's
} pc;

// P5 §3.2: the gaze at rho = 0 and rho scaled so that rho = 1 reaches the farthest corner.
VisualPolarMap makeMap(uint eye, uvec2 vpSize, uint eyes) {
    VisualPolarMap m;
    m.screen = vec2(max(cameraEyeSize(), uvec2(1u)));
    m.width = max(vpSize.x / max(eyes, 1u), 1u);
    m.height = max(vpSize.y, 1u);
    m.foveaFraction = pc.foveaFraction;
    m.foveaDegrees = pc.foveaDegrees;
    m.stairBlock = pc.stairBlock;
    m.stairPhase = vpStairPhaseOf(pc.stairBlock, pc.stairOffset, eye, m.width);
    m.stairPrevPhase = vpStairPhaseOf(pc.stairBlock, pc.stairPrevOffset, eye, m.width);
    return vpWithGaze(m, clamp(camera_info.eyes[eye].gaze.xy, 0.0, 1.0) * m.screen);  // clamped
}

void main() {
    uvec2 size = uvec2(imageSize(coords));
    uint eyes = clamp(cameraEyeCount(), 1u, 2u);
    uvec2 p = gl_GlobalInvocationID.xy;
    if (all(equal(p, uvec2(0u)))) {
        VisualPolarMap m0 = makeMap(0u, size, eyes);
        VisualPolarMap m1 = makeMap(min(1u, eyes - 1u), size, eyes);
        vp.grid = uvec4(m0.width, m0.height, eyes, 1u);
        vp.fovea = vec4(m0.foveaFraction, m0.foveaDegrees, m0.screen);
        vp.eyes[0] = vec4(m0.gaze, m0.dMax, 0.0);
        vp.eyes[1] = vec4(m1.gaze, m1.dMax, 0.0);
        vp.stair = uvec4(pc.stairBlock, pc.stairOffset, pc.stairPrevOffset, 0u);
    }
    if (any(greaterThanEqual(p, size))) return;
    uint vpWidth = max(size.x / eyes, 1u);
    uint eye = min(p.x / vpWidth, eyes - 1u);
    VisualPolarMap m = makeMap(eye, size, eyes);
    uint column = p.x - eye * vpWidth;
    // An odd side-by-side width leaves one column beyond the last eye: never traced.
    if (column >= m.width || p.y >= vpRows(m, column)) {
        imageStore(coords, ivec2(p), vec4(-1.0, -1.0, 0.0, float(eye)));
        return;
    }
    vec2 s = vpTexelToScreen(m, uvec2(column, p.y), vec2(0.0));
    bool onScreen = all(greaterThanEqual(s, vec2(0.0))) && all(lessThan(s, m.screen));
    float traced = (onScreen || pc.traceOffscreen != 0u) ? 1.0 : 0.0;
    float eyeOffset = float(eye * cameraEyeSize().x);
    imageStore(coords, ivec2(p), vec4(s.x + eyeOffset, s.y, traced, float(eye)));
}
