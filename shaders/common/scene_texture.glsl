// Texture lookups of the scene (docs/scene-gpu.md): RGBA8 texels with sRGB decoding, the glTF
// sampler's wrap modes and filters, and each material slot's view (KHR_texture_transform). The
// CPU reference is core/scene/TextureSampling.cpp. Included by scene_sample.glsl.
#ifndef FOVEA_SCENE_TEXTURE_GLSL
#define FOVEA_SCENE_TEXTURE_GLSL

#include "scene_data.glsl"

// IEC 61966-2-1 decode; c is a unorm value in [0, 1], so pow's base is >= 0.055 / 1.055 > 0.
vec3 sceneSrgbToLinear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}

#if SCENE_HAS_TEXTURES
vec4 sceneTexel(SceneTexture tex, uint x, uint y, bool srgb) {
    vec4 t = unpackUnorm4x8(scene_texels.texels[tex.offset + y * tex.width + x]);
    return srgb ? vec4(sceneSrgbToLinear(t.rgb), t.a) : t;
}
#endif

// Texture slots of a material, in scene_texture_views order (SceneGpu.cpp).
const uint kSceneTextureSlots = 4u;
const uint kSceneSlotBaseColor = 0u;
const uint kSceneSlotMetallicRoughness = 1u;
const uint kSceneSlotEmissive = 2u;
const uint kSceneSlotNormal = 3u;
const uint kSceneViewNearest = 16u;
const uint kSceneViewTransformed = 32u;

#if SCENE_HAS_TEXTURES
// The coordinate brought into a range the wrap mode maps the same way (huge UVs would overflow
// the int texel index): one period for repeat (fract: the texel index lands in [-1, size]), two
// for mirrored repeat ([-1, 2 size]), [-1, 2] for clamp-to-edge. As TextureSampling.cpp.
float sceneReduceCoordinate(float x, uint wrap) {
    if (wrap == 1u) return clamp(x, -1.0, 2.0);
    if (wrap == 2u) return x - 2.0 * floor(0.5 * x);
    return fract(x);
}

// Texel index i (in the reduced ranges above) wrapped into [0, size). GLSL's % is undefined for
// negative operands, hence the explicit periods. The final clamp keeps NaN UVs (undefined int
// conversion) inside the texture.
int sceneWrapTexel(int i, int size, uint wrap) {
    if (wrap == 1u) return clamp(i, 0, size - 1);
    if (wrap == 2u) {
        int m = i < 0 ? i + 2 * size : (i >= 2 * size ? i - 2 * size : i);
        i = m < size ? m : 2 * size - 1 - m;
    } else {
        i = i < 0 ? i + size : (i >= size ? i - size : i);
    }
    return clamp(i, 0, size - 1);
}
#endif

// Sample with the sampler `flags` (SceneTextureView.flags; 0 = repeat, bilinear), texel centres
// at (i + 0.5) / size, top row = v 0 (glTF). sRGB textures are decoded per texel before
// filtering, so filtering happens in linear space. Returns vec4(1) for texture -1 or a texture
// without texels, so factors pass through. With flags 0 this is exactly the bilinear repeat
// lookup fovea always had (goldens unchanged).
vec4 sceneSampleTextureFlags(int texture, vec2 uv, bool srgb, uint flags) {
#if SCENE_HAS_TEXTURES
    if (texture < 0 || uint(texture) >= scene_info.textureCount) return vec4(1.0);
    SceneTexture tex = scene_textures.textures[texture];
    if (tex.width == 0u || tex.height == 0u) return vec4(1.0);
    uint wrapS = flags & 3u, wrapT = (flags >> 2) & 3u;
    ivec2 size = ivec2(tex.width, tex.height);
    vec2 reduced = vec2(sceneReduceCoordinate(uv.x, wrapS), sceneReduceCoordinate(uv.y, wrapT));
    if ((flags & kSceneViewNearest) != 0u) {
        ivec2 i = ivec2(floor(reduced * vec2(size)));
        return sceneTexel(tex, uint(sceneWrapTexel(i.x, size.x, wrapS)),
                          uint(sceneWrapTexel(i.y, size.y, wrapT)), srgb);
    }
    vec2 st = reduced * vec2(size) - 0.5;
    vec2 cell = floor(st);
    vec2 f = st - cell;
    ivec2 i0 = ivec2(cell);
    ivec2 lo = ivec2(sceneWrapTexel(i0.x, size.x, wrapS), sceneWrapTexel(i0.y, size.y, wrapT));
    ivec2 hi = ivec2(sceneWrapTexel(i0.x + 1, size.x, wrapS),
                     sceneWrapTexel(i0.y + 1, size.y, wrapT));
    vec4 t00 = sceneTexel(tex, uint(lo.x), uint(lo.y), srgb);
    vec4 t10 = sceneTexel(tex, uint(hi.x), uint(lo.y), srgb);
    vec4 t01 = sceneTexel(tex, uint(lo.x), uint(hi.y), srgb);
    vec4 t11 = sceneTexel(tex, uint(hi.x), uint(hi.y), srgb);
    return mix(mix(t00, t10, f.x), mix(t01, t11, f.x), f.y);
#else
    return vec4(1.0);
#endif
}

// Bilinear, repeat: the glTF default sampler without a texture transform.
vec4 sceneSampleTexture(int texture, vec2 uv, bool srgb) {
    return sceneSampleTextureFlags(texture, uv, srgb, 0u);
}

// Texture slot `slot` of `material` read through its view: KHR_texture_transform, then the
// glTF sampler (core/scene/TextureSampling.cpp is the CPU reference).
vec4 sceneSampleMaterialTexture(uint material, uint slot, int texture, vec2 uv, bool srgb) {
#if SCENE_HAS_TEXTURES
    if (texture < 0) return vec4(1.0);
    SceneTextureView v = scene_texture_views.views[material * kSceneTextureSlots + slot];
    if ((v.flags & kSceneViewTransformed) != 0u)
        uv = vec2(dot(v.row0, vec3(uv, 1.0)), dot(v.row1, vec3(uv, 1.0)));
    return sceneSampleTextureFlags(texture, uv, srgb, v.flags);
#else
    return vec4(1.0);
#endif
}

#endif
