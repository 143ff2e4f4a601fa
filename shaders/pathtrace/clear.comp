#version 460
// PathTrace with a sample layout: every pixel starts invalid (a = 0, all zero) before the listed
// pixels are traced (CONTRACT "Sample layout"), so no pixel keeps stale radiance.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8) in;

layout(rgba32f) uniform writeonly image2D radiance;
layout(rgba32f) uniform writeonly image2D demodulated;
layout(r32f) uniform writeonly image2D hit_distance;
layout(rgba16f) uniform writeonly image2D direct;
layout(rgba16f) uniform writeonly image2D indirect;
layout(rgba32f) uniform writeonly image2D diffuse;
layout(rgba32f) uniform writeonly image2D specular;
layout(rgba16f) uniform writeonly image2D diffuse_albedo;
layout(rgba16f) uniform writeonly image2D specular_albedo;
layout(r16f) uniform writeonly image2D diffuse_hit;
layout(r16f) uniform writeonly image2D specular_hit;

layout(push_constant) uniform Params {
    ivec2 size;
} pc;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, pc.size))) return;
    imageStore(radiance, p, vec4(0.0));
    imageStore(demodulated, p, vec4(0.0));
    imageStore(hit_distance, p, vec4(0.0));
    imageStore(direct, p, vec4(0.0));
    imageStore(indirect, p, vec4(0.0));
    imageStore(diffuse, p, vec4(0.0));
    imageStore(specular, p, vec4(0.0));
    imageStore(diffuse_albedo, p, vec4(0.0));
    imageStore(specular_albedo, p, vec4(0.0));
    imageStore(diffuse_hit, p, vec4(-1.0));  // no ray: no data
    imageStore(specular_hit, p, vec4(-1.0));
}
