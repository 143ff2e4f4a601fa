#include "core/scene/TextureSampling.h"

#include <algorithm>
#include <cmath>

#include "core/scene/LightTable.h"

namespace fovea::scene {
namespace {

// The coordinate brought into a small range that the wrap mode maps the same way (so that huge
// UVs neither overflow an int nor lose the texel): one period for repeat, two for mirrored
// repeat; clamp-to-edge reads the edge texel anywhere outside [0, 1].
float reduceCoordinate(float x, TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::ClampToEdge:
            return std::clamp(x, -1.0f, 2.0f);
        case TextureWrap::MirroredRepeat:
            return x - 2.0f * std::floor(0.5f * x);
        case TextureWrap::Repeat:
            break;
    }
    return x - std::floor(x);
}

}  // namespace

int wrapTexel(int i, int size, TextureWrap wrap) {
    switch (wrap) {
        case TextureWrap::ClampToEdge:
            return std::clamp(i, 0, size - 1);
        case TextureWrap::MirroredRepeat: {
            // Period 2 size: 0 .. size-1, then size-1 .. 0 (OpenGL 4.6 §8.14.2, mirror(a)).
            const int m = ((i % (2 * size)) + 2 * size) % (2 * size);
            return m < size ? m : 2 * size - 1 - m;
        }
        case TextureWrap::Repeat:
            break;
    }
    return ((i % size) + size) % size;
}

glm::vec4 sampleTexture(const Texture& t, const TextureView& view, glm::vec2 uv, bool srgb) {
    if (t.width == 0 || t.height == 0 || t.rgba8.size() < size_t(t.width) * t.height * 4)
        return glm::vec4(1.0f);
    auto texel = [&](int x, int y) {
        x = wrapTexel(x, int(t.width), view.sampler.wrapS);
        y = wrapTexel(y, int(t.height), view.sampler.wrapT);
        const uint8_t* p = &t.rgba8[(size_t(y) * t.width + size_t(x)) * 4];
        glm::vec4 c(p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f, p[3] / 255.0f);
        if (srgb)
            for (int k = 0; k < 3; ++k) c[k] = float(LightTable::srgbToLinear(c[k]));
        return c;
    };
    const glm::vec2 size(float(t.width), float(t.height));
    const glm::vec2 transformed = view.transform.apply(uv);
    if (!std::isfinite(transformed.x) || !std::isfinite(transformed.y)) return texel(0, 0);
    const glm::vec2 st = glm::vec2(reduceCoordinate(transformed.x, view.sampler.wrapS),
                                   reduceCoordinate(transformed.y, view.sampler.wrapT)) *
                         size;
    if (view.sampler.nearest) return texel(int(std::floor(st.x)), int(std::floor(st.y)));
    const glm::vec2 centred = st - 0.5f;
    const glm::vec2 cell = glm::floor(centred);
    const glm::vec2 f = centred - cell;
    const int x0 = int(cell.x), y0 = int(cell.y);
    const glm::vec4 top = glm::mix(texel(x0, y0), texel(x0 + 1, y0), f.x);
    const glm::vec4 bottom = glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), f.x);
    return glm::mix(top, bottom, f.y);
}

}  // namespace fovea::scene
