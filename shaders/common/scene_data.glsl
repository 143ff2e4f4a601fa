// The scene buffers core/scene/SceneGpu uploads, by the fixed names SceneGpu::bind() looks for.
// Every struct mirrors fovea::scene::layout (core/scene/SceneGpu.h), BvhNode (core/scene/Bvh.h)
// and EmitterEntry (core/scene/LightTable.h); their sizes are static_asserted there. A vec3
// followed by a 4-byte scalar shares one 16-byte slot in std430, exactly like glm::vec3 + float.
//
// Compile with SceneGpu::defines(): SCENE_HAS_TEXTURES / SCENE_HAS_EMISSIVE / SCENE_HAS_PUNCTUAL
// / SCENE_HAS_VERTEX_COLORS / SCENE_HAS_NORMAL_MAPS / SCENE_HAS_ENVIRONMENT / SCENE_HAS_ALPHA = 0
// drop the buffers and code paths a scene does not need. Without defines everything is on,
// which is valid for any scene (empty buffers
// are still bound; an empty scene_vertex_colors reads as white, see sceneVertexColor; an empty
// scene_environment has width 0 and emits nothing).
#ifndef FOVEA_SCENE_DATA_GLSL
#define FOVEA_SCENE_DATA_GLSL
// The four arrays that grow with the triangle count (vertices, triangles, BVH nodes and
// intersection positions) are storage bindings, unless one of them is larger than a descriptor
// may bind (maxStorageBufferRange: 128 MiB on lavapipe, which a 10M-triangle scene's BVH alone
// exceeds; issue 28). Then SceneGpu defines SCENE_GEOMETRY_BY_ADDRESS 1 and they are read through
// the device addresses in scene_info. Not always: on lavapipe the address path traverses 15-20 %
// slower (docs/scene-gpu.md).
#ifndef SCENE_GEOMETRY_BY_ADDRESS
#define SCENE_GEOMETRY_BY_ADDRESS 0
#endif
#if SCENE_GEOMETRY_BY_ADDRESS
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#endif

#ifndef SCENE_HAS_TEXTURES
#define SCENE_HAS_TEXTURES 1
#endif
#ifndef SCENE_HAS_EMISSIVE
#define SCENE_HAS_EMISSIVE 1
#endif
#ifndef SCENE_HAS_PUNCTUAL
#define SCENE_HAS_PUNCTUAL 1
#endif
#ifndef SCENE_HAS_VERTEX_COLORS
#define SCENE_HAS_VERTEX_COLORS 1
#endif
#ifndef SCENE_HAS_NORMAL_MAPS
#define SCENE_HAS_NORMAL_MAPS 1  // without one, textures.w is -1 everywhere: nothing is mapped
#endif
#ifndef SCENE_HAS_ENVIRONMENT
#define SCENE_HAS_ENVIRONMENT 1  // without one, scene_environment's width is 0: nothing emits
#endif
#ifndef SCENE_HAS_ALPHA
// Alpha-tested materials (glTF MASK / BLEND): the traversal's any-hit test in bvh.glsl. On for a
// scene without any, it only reads each candidate hit's v0.w flag (0 for opaque triangles).
#define SCENE_HAS_ALPHA 1
#endif

const uint kBvhInternalNode = 0xFFFFFFFFu;  // BvhNode.count of an internal node
const uint kBvhMaxDepth = 48u;              // = Bvh::kMaxDepth; sizes the traversal stack
const uint kEmitterPunctualBit = 0x80000000u;
const uint kLightPoint = 0u;
const uint kLightSpot = 1u;
const uint kLightDirectional = 2u;

struct SceneVertex {
    vec4 positionU;  // xyz position, w = uv.x
    vec4 normalV;    // xyz shading normal (may be zero), w = uv.y
};

struct SceneTriangle {
    uvec3 indices;  // into scene_vertices
    uint material;  // into scene_materials
};

// Depth-first: an internal node's left child is the next node, `index` is the right child.
// A leaf (count != kBvhInternalNode) holds triangles [index, index + count).
struct BvhNode {
    vec3 boundsMin;
    uint index;
    vec3 boundsMax;
    uint count;
};

struct SceneMaterial {
    vec4 baseColor;  // linear RGBA factor
    vec4 emissive;   // rgb linear factor; w = emitted power per unit area (light selection)
    vec4 params;     // x metallic, y roughness, z doubleSided (0/1), w alpha threshold: 0 opaque,
                     // > 0 MASK cutoff, < 0 BLEND (sceneAlphaPassesThrough)
    ivec4 textures;  // x baseColor (sRGB), y metallicRoughness (linear), z emissive (sRGB),
                     // w normal (linear, tangent space); -1 none
};

struct SceneTexture {
    uint offset;  // first texel in scene_texels
    uint width;   // 0 = no texels
    uint height;
    uint flags;
};

// How a material's texture slot reads its texture (layout::TextureView, TextureView.h): the 2x3
// KHR_texture_transform matrix and the sampler flags (bits 0-1 wrapS, 2-3 wrapT: 0 repeat,
// 1 clamp-to-edge, 2 mirrored repeat; bit 4 nearest; bit 5 the transform is not the identity).
struct SceneTextureView {
    vec3 row0;  // u' = dot(row0, vec3(u, v, 1))
    uint flags;
    vec3 row1;  // v' = dot(row1, vec3(u, v, 1))
    float scale;  // the normal slot: normalTexture.scale (glTF 2.0 §3.9.3); 1 elsewhere
};

struct SceneLight {
    vec3 position;
    float range;  // 0 = infinite
    vec3 direction;  // the way the light shines
    uint type;       // kLightPoint / kLightSpot / kLightDirectional
    vec3 intensity;  // color * intensity (candela; lux for directional)
    float spotScale;
    float spotOffset;
    float pad0;
    float pad1;
    float pad2;
};

// One alias-table column over all lights (emissive triangles and punctual lights).
struct SceneEmitter {
    uint light;       // GPU triangle index, or kEmitterPunctualBit | scene_lights index
    uint alias;       // column taken when the coin fails
    float aliasProb;  // probability of keeping this column
    float pdf;        // selection probability of this light (power / total power)
};

// Explicit bindings 16-25 and 27-31 (26 is camera.glsl's CameraInfo): the compiler's automatic numbering only numbers resources a shader
// uses, and leaves unused ones (a pass that never samples textures still declares
// scene_texels) at binding 0, where they would collide. glslang reserves explicit slots first, so
// a pass's own auto-numbered resources flow around this range.
layout(std140, binding = 16) uniform SceneInfo {
    uint vertexCount;
    uint triangleCount;
    uint nodeCount;
    uint materialCount;
    uint textureCount;
    uint texelCount;
    uint lightCount;
    uint emitterCount;
    uint emissiveTriangleCount;
    uint features;
    uint invalidTriangles;
    uint vertexColors;  // 1: scene_vertex_colors holds one entry per vertex
    float totalPower;
    float emissivePower;
    float punctualPower;
    float radius;  // of the scene's bounding sphere
    vec4 boundsMin;
    vec4 boundsMax;
    uvec2 vertexAddress;  // device addresses of the arrays below (low, high word)
    uvec2 triangleAddress;
    uvec2 nodeAddress;
    uvec2 bvhTriangleAddress;
} scene_info;

#if SCENE_GEOMETRY_BY_ADDRESS
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SceneVertexArray {
    SceneVertex vertices[];
};
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SceneTriangleArray {
    SceneTriangle triangles[];
};
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SceneBvhNodeArray {
    BvhNode nodes[];
};
// Per GPU triangle: v0, v1 - v0, v2 - v0 (3 vec4s): the leaf loop streams them contiguously.
// v0.w = 1 when the triangle's material is alpha-tested (params.w != 0), else 0.
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SceneBvhPositionArray {
    vec4 positions[];
};
// The host names them scene_vertices, scene_triangles, scene_bvh, scene_bvh_triangles
// (SceneGpu::buffer); indices are in range by construction (BVH build and upload).
SceneVertex sceneVertex(uint i) {
    return SceneVertexArray(scene_info.vertexAddress).vertices[i];
}
SceneTriangle sceneTriangle(uint i) {
    return SceneTriangleArray(scene_info.triangleAddress).triangles[i];
}
BvhNode sceneBvhNode(uint i) {
    return SceneBvhNodeArray(scene_info.nodeAddress).nodes[i];
}
vec4 sceneBvhPosition(uint i) {
    return SceneBvhPositionArray(scene_info.bvhTriangleAddress).positions[i];
}
#else
layout(std430, binding = 17) readonly buffer SceneVertices {
    SceneVertex vertices[];
} scene_vertices;
layout(std430, binding = 18) readonly buffer SceneTriangles {
    SceneTriangle triangles[];
} scene_triangles;
layout(std430, binding = 19) readonly buffer SceneBvh {
    BvhNode nodes[];
} scene_bvh;
// Per GPU triangle: v0, v1 - v0, v2 - v0 (3 vec4s): the leaf loop streams them contiguously.
// v0.w = 1 when the triangle's material is alpha-tested (params.w != 0), else 0.
layout(std430, binding = 20) readonly buffer SceneBvhTriangles {
    vec4 positions[];
} scene_bvh_triangles;
SceneVertex sceneVertex(uint i) {
    return scene_vertices.vertices[i];
}
SceneTriangle sceneTriangle(uint i) {
    return scene_triangles.triangles[i];
}
BvhNode sceneBvhNode(uint i) {
    return scene_bvh.nodes[i];
}
vec4 sceneBvhPosition(uint i) {
    return scene_bvh_triangles.positions[i];
}
#endif
layout(std430, binding = 21) readonly buffer SceneMaterials {
    SceneMaterial materials[];
} scene_materials;

#if SCENE_HAS_TEXTURES
layout(std430, binding = 22) readonly buffer SceneTextures {
    SceneTexture textures[];
} scene_textures;
// RGBA8 texels, R in the low byte (unpackUnorm4x8).
layout(std430, binding = 23) readonly buffer SceneTexels {
    uint texels[];
} scene_texels;
// kSceneTextureSlots views per material (base colour, metallic-roughness, emissive, normal), in
// scene_materials order.
layout(std430, binding = 30) readonly buffer SceneTextureViews {
    SceneTextureView views[];
} scene_texture_views;
#endif

#if SCENE_HAS_PUNCTUAL
layout(std430, binding = 24) readonly buffer SceneLights {
    SceneLight lights[];
} scene_lights;
#endif

#if SCENE_HAS_EMISSIVE || SCENE_HAS_PUNCTUAL
layout(std430, binding = 25) readonly buffer SceneEmitters {
    SceneEmitter emitters[];
} scene_emitters;
#endif

#if SCENE_HAS_ENVIRONMENT
// Environment light (core/scene/Environment.h, layout::EnvironmentHeader): per texel rgb
// radiance and a = its selection probability P_ij; the alias tables (rows, then each row's
// columns) draw a texel in O(1). Functions: common/environment.glsl.
layout(std430, binding = 28) readonly buffer SceneEnvironment {
    uint width;
    uint height;
    float rotation;           // radians about +Y
    float selectProbability;  // of the environment in next-event estimation
    float pdfScale;           // W H / (2 pi^2)
    float luminanceIntegral;
    float pad0;
    float pad1;
    vec4 texels[];
} scene_environment;
layout(std430, binding = 29) readonly buffer SceneEnvironmentAlias {
    // height row slots, then width column slots per row: x alias index (row, or column within
    // the row), y floatBitsToUint(keep probability)
    uvec2 alias[];
} scene_environment_alias;
#endif

#if SCENE_HAS_NORMAL_MAPS
// Tangent frames per vertex (scene_vertices order) for normal textures: xyz unit tangent along +u,
// w = +-1 the bitangent's sign (glTF TANGENT, or generated: core/scene/Tangents.h). A 16-byte
// dummy when no material is normal-mapped.
layout(std430, binding = 31) readonly buffer SceneTangents {
    vec4 tangents[];
} scene_tangents;
#endif

#if SCENE_HAS_VERTEX_COLORS
// glTF COLOR_0 per vertex (in scene_vertices order): packUnorm2x16(rg), packUnorm2x16(ba).
// Empty (one 16-byte dummy) when the mesh has no colours.
layout(std430, binding = 27) readonly buffer SceneVertexColors {
    uvec2 colors[];
} scene_vertex_colors;
#endif

#endif
