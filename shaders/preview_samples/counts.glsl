// PreviewSamples' internal `counts` buffer: the number of samples that landed in each equirect
// texel this frame (row-major).
#ifndef FOVEA_PREVIEW_COUNTS_GLSL
#define FOVEA_PREVIEW_COUNTS_GLSL
layout(std430) buffer Counts {
    uint texels[];
} counts;
#endif
