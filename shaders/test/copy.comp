#version 460
// Test shader: copies a sampled image into a storage image (texelFetch, so no filtering).
layout(local_size_x = 16, local_size_y = 4) in;

layout(set = 0, binding = 0) uniform sampler2D src;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D dst;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(dst)))) return;
    imageStore(dst, p, texelFetch(src, p, 0));
}
