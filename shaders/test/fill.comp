#version 460
// Test shader: writes a push-constant colour into every pixel of a storage image.
// ADD_COORDS adds the pixel coordinate to .xy (used to check defines and exact addressing).
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform writeonly image2D result;

layout(push_constant) uniform Push {
    vec4 value;
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, imageSize(result)))) return;
    vec4 v = pc.value;
#ifdef ADD_COORDS
    v.xy += vec2(p);
#endif
    imageStore(result, p, v);
}
