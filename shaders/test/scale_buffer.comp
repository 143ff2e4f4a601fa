#version 460
// Test shader: output[i] = input[i] * scale + offset for i < count. The input block has an
// instance name, the output block does not (reflection names them "inputData" / "Output").
layout(local_size_x = 64) in;

layout(set = 0, binding = 0, std430) readonly buffer Input {
    float values[];
} inputData;

layout(set = 0, binding = 1, std430) writeonly buffer Output {
    float outValues[];
};

layout(push_constant) uniform Push {
    float scale;
    uint count;
    vec2 offset;  // .x is added; vec2 exercises 8-byte alignment
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;
    outValues[i] = inputData.values[i] * pc.scale + pc.offset.x;
}
