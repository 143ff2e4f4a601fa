#include "tests/graph/ATrousReference.h"

#include <algorithm>
#include <cmath>

namespace fovea::testref {

namespace {
constexpr float kB3[5] = {1.0f / 16.0f, 1.0f / 4.0f, 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f};

float invSquare(float sigma) {
    return sigma > 0.0f ? 1.0f / (sigma * sigma) : 0.0f;
}

float edgeWeight(float d2, float invSigma2) {
    float w = std::exp(-d2 * invSigma2);
    return std::isnan(w) ? 0.0f : w;
}

float dist2(const float* a, const float* b) {
    float d = 0.0f;
    for (int c = 0; c < 3; ++c) d += (a[c] - b[c]) * (a[c] - b[c]);
    return d;
}

// Squared distance of xq to the plane through xp with normal np (the shader's plane term).
float planeDist2(const float* np, const float* xp, const float* xq) {
    if (xp[3] != xq[3]) return 1e30f;  // hit next to miss
    float t = 0.0f;
    for (int c = 0; c < 3; ++c) t += np[c] * (xq[c] - xp[c]);
    return t * t;
}
}  // namespace

std::vector<float> atrousReference(const ATrousRefInput& in) {
    const int w = in.width, h = in.height;
    const size_t n = size_t(w) * h;
    const bool useMask = !in.mask.empty();
    const int eyes = std::max(in.eyes, 1);
    const int eyeWidth = w / eyes;
    const float invC = invSquare(in.sigmaColor);
    const float invN = in.normal.empty() ? 0.0f : invSquare(in.sigmaNormal);
    const float invX = in.position.empty() ? 0.0f : invSquare(in.sigmaPosition);
    const float invT = in.position.empty() ? 0.0f : invSquare(in.sigmaTangent);

    // State: rgb + validity, initialised as the shader's loadState from the input.
    std::vector<float> state(n * 4, 0.0f);
    for (size_t i = 0; i < n; ++i) {
        const float* color = &in.color[i * 4];
        bool ok = color[3] > 0.0f;
        for (int k = 0; k < 4; ++k) ok = ok && std::isfinite(color[k]);
        if (useMask) ok = ok && (in.mask[i] & 1u) != 0u;
        if (!ok) continue;
        for (int c = 0; c < 3; ++c) state[i * 4 + c] = color[c];
        state[i * 4 + 3] = 1.0f;
    }
    auto layerOf = [&](size_t i) {
        if (!useMask || in.layerCount <= 1) return 0;
        return int(std::min<uint32_t>((in.mask[i] >> 1) & 3u, uint32_t(in.layerCount - 1)));
    };

    std::vector<float> next(n * 4);
    for (const auto& d : in.schedule) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t i = size_t(y) * w + x;
                const float* centre = &state[i * 4];
                const bool centreValid = centre[3] > 0.5f;
                const bool active = d.fill ? !centreValid : ((d.layers >> layerOf(i)) & 1u) != 0u;
                float* out = &next[i * 4];
                std::copy(centre, centre + 4, out);
                if (!active) continue;
                const int eye = std::min(x / eyeWidth, eyes - 1);
                const int x0 = eye * eyeWidth, x1 = eye == eyes - 1 ? w : x0 + eyeWidth;
                const float invN2 = invN / float(d.step * d.step);
                float sum[3] = {0, 0, 0}, plain[3] = {0, 0, 0}, cum = 0.0f, plainCum = 0.0f;
                for (int dy = -2; dy <= 2; ++dy)
                    for (int dx = -2; dx <= 2; ++dx) {
                        const int qx = x + d.step * dx, qy = y + d.step * dy;
                        if (qx < x0 || qx >= x1 || qy < 0 || qy >= h) continue;
                        const size_t j = size_t(qy) * w + qx;
                        const float* s = &state[j * 4];
                        if (s[3] <= 0.5f) continue;
                        const float hk = kB3[dx + 2] * kB3[dy + 2];
                        float wt = 1.0f;
                        if (centreValid && invC > 0.0f) wt *= edgeWeight(dist2(centre, s), invC);
                        if (invN > 0.0f)
                            wt *= edgeWeight(dist2(&in.normal[i * 4], &in.normal[j * 4]), invN2);
                        if (invX > 0.0f) {
                            const float* xp = &in.position[i * 4];
                            const float* xq = &in.position[j * 4];
                            float d2 = dist2(xp, xq);
                            if (in.positionPlane) {
                                const float t2 = planeDist2(&in.normal[i * 4], xp, xq);
                                wt *= edgeWeight(std::max(d2 - t2, 0.0f), invT);
                                d2 = t2;
                            }
                            wt *= edgeWeight(d2, invX);
                        }
                        for (int c = 0; c < 3; ++c) {
                            sum[c] += s[c] * (wt * hk);
                            plain[c] += s[c] * hk;
                        }
                        cum += wt * hk;
                        plainCum += hk;
                    }
                if (cum > 1e-30f) {
                    for (int c = 0; c < 3; ++c) out[c] = sum[c] / cum;
                    out[3] = 1.0f;
                } else if (!centreValid && plainCum > 0.0f) {
                    for (int c = 0; c < 3; ++c) out[c] = plain[c] / plainCum;
                    out[3] = 1.0f;
                }
            }
        state.swap(next);
    }
    return state;
}

}  // namespace fovea::testref
