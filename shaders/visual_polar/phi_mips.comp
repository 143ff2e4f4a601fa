#version 460
// Unwarp step 1 (seed 003 P5 §3.4): mipmaps along phi only. Level k of column i has
// ceil(n_i / 2^k) rows; row j is the mean of rows 2j and 2j + 1 of level k - 1, the second
// wrapped onto row 0 when the level above has an odd height (phi is periodic). rho is never
// filtered: P5 finds it one-to-one or magnified.
#extension GL_GOOGLE_include_directive : require

#define VISUAL_POLAR_PARAMS
#include "../common/visual_polar.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;  // level 0
layout(rgba32f) uniform image2D mip1;
layout(rgba32f) uniform image2D mip2;
layout(rgba32f) uniform image2D mip3;

layout(push_constant) uniform Params {
    uint level;  // 1..3: the level written
} pc;

vec4 loadLevel(uint level, ivec2 p) {
    if (level == 0u) return texelFetch(color, p, 0);
    if (level == 1u) return imageLoad(mip1, p);
    return imageLoad(mip2, p);
}

// Dispatched indirectly by unwarp_lookup.comp (mode 2): x covers the columns the fine mapping
// reads (from column 0), z is the eye; a level the mapping never reads gets no groups (P5 §3.4:
// at reduction 0.61 and a centre gaze only level 1 is built).
void main() {
    ivec2 size = textureSize(color, 0);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    uint eyes = clamp(vp.grid.z, 1u, 2u);
    uint eye = min(gl_WorkGroupID.z, eyes - 1u);
    VisualPolarMap m = vpMapOfEye(eye);  // its own staircase phase (P5 §3.3)
    uint column = uint(p.x);
    if (column >= m.width) return;
    p.x = int(eye * m.width + column);
    if (p.x >= size.x) return;
    uint above = vpRowsAtLevel(m, column, pc.level - 1u);
    uint rows = vpRowsAtLevel(m, column, pc.level);  // ceil(above / 2)
    if (uint(p.y) >= rows) return;
    uint j0 = 2u * uint(p.y), j1 = (j0 + 1u) % above;  // above >= 1
    vec4 v = 0.5 * (loadLevel(pc.level - 1u, ivec2(p.x, j0)) + loadLevel(pc.level - 1u, ivec2(p.x, j1)));
    if (pc.level == 1u) imageStore(mip1, p, v);
    else if (pc.level == 2u) imageStore(mip2, p, v);
    else imageStore(mip3, p, v);
}
