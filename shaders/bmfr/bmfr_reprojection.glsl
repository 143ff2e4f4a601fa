// BMFR phases I and III (seed 003 P2 §3.2, §3.5): where the 4 bilinear history taps of a
// reprojected pixel are. Both phases call this with the same arguments, so phase III reuses
// phase I's per-tap accept mask tap for tap.
#ifndef FOVEA_BMFR_REPROJECTION_GLSL
#define FOVEA_BMFR_REPROJECTION_GLSL
#define VISUAL_POLAR_PARAMS
#include "common/visual_polar.glsl"

// The 4 bilinear taps around the previous position `prev` (pixel centres at +0.5) and their
// weights. Visual-Polar (seed 003 P5 §3.3): `prev` is (x in columns of the whole image, t = phi /
// 2 pi) and the taps follow each column's own phi height, wrapped (visual_polar.glsl).
void bmfrHistoryTaps(bool useVp, ivec2 size, vec2 prev, out ivec2 taps[4], out float weights[4]) {
    if (useVp) {
        uint eye = vpEyeOfColumn(prev.x);
        // The previous image was traced with the previous frame's phi heights (staircase).
        VisualPolarMap m = vpPrevious(vpMapOfEye(eye));
        float x0 = float(eye * m.width);
        vpBilinearTaps(m, prev - vec2(x0, 0.0), taps, weights);
        for (int i = 0; i < 4; ++i) taps[i].x += int(x0);
        return;
    }
    vec2 q = prev - 0.5;
    // |q| is bounded by cameraPreviousPixel's finite result; floor of a huge value is still a
    // tap outside the image, which the bounds test rejects.
    ivec2 base = ivec2(floor(clamp(q, vec2(-2.0), vec2(size) + 1.0)));
    vec2 f = clamp(q - vec2(base), 0.0, 1.0);
    for (int i = 0; i < 4; ++i) {
        ivec2 o = ivec2(i & 1, i >> 1);
        taps[i] = base + o;
        weights[i] = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
    }
}

#endif
