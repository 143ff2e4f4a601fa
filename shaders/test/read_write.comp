#version 460
// Test shader: read-modify-write of a storage image that must carry a format qualifier
// (lavapipe has no shaderStorageImageReadWithoutFormat), plus a uniform buffer.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba16f) uniform image2D target;
layout(set = 0, binding = 1, std140) uniform Params {
    vec4 add;
} params;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(target)))) return;
    imageStore(target, p, imageLoad(target, p) + params.add);
}
