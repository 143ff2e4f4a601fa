#version 460
// Blit: resample an image to another size/format (nearest or bilinear).
layout(local_size_x = 8, local_size_y = 8) in;

uniform sampler2D color;
uniform writeonly image2D result;  // any format: shaderStorageImageWriteWithoutFormat

layout(push_constant) uniform Params {
    ivec2 size;
    int linear;
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    // size >= 1 (guarded in p check above), so the division is safe.
    vec2 uv = (vec2(p) + 0.5) / vec2(pc.size);
    ivec2 srcSize = textureSize(color, 0);
    vec4 c = pc.linear != 0 ? textureLod(color, uv, 0.0)
                            : texelFetch(color, min(ivec2(uv * vec2(srcSize)), srcSize - 1), 0);
    imageStore(result, p, c);
}
