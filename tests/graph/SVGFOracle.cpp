#include "tests/graph/SVGFOracle.h"

#include <algorithm>
#include <cmath>

namespace fovea::testsvgf {

namespace {

double depthAt(const std::vector<float>& d, int w, int x, int y) {
    const double z = d[(size_t(y) * size_t(w) + size_t(x)) * 4];
    return (std::isfinite(z) && z > 0.0) ? z : 0.0;
}

// As svgfDepthGradient: per axis the one-sided difference with the smaller magnitude.
void depthGradient(const std::vector<float>& d, int w, int h, int x, int y, double zp,
                   double g[2]) {
    for (int a = 0; a < 2; ++a) {
        bool found = false;
        double best = 0.0;
        for (int s = -1; s <= 1; s += 2) {
            const int qx = x + (a == 0 ? s : 0), qy = y + (a == 1 ? s : 0);
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const double zq = depthAt(d, w, qx, qy);
            if (zq <= 0.0) continue;
            const double diff = double(s) * (zq - zp);
            if (!found || std::fabs(diff) < std::fabs(best)) best = diff;
            found = true;
        }
        g[a] = best;
    }
}

double depthWeight(double zp, double zq, const double g[2], double ox, double oy, double sz) {
    const double den = sz * std::fabs(g[0] * ox + g[1] * oy) + 1e-5 * zp;
    return std::exp(-std::fabs(zp - zq) / den);
}

double normalWeight(const float* np, const float* nq, double sn) {
    if (sn <= 0.0) return 1.0;
    const double d = double(np[0]) * nq[0] + double(np[1]) * nq[1] + double(np[2]) * nq[2];
    return std::pow(std::max(0.0, d), sn);
}

constexpr double kB3[3] = {3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0};

}  // namespace

double luminance709(const double* c) {
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

std::vector<double> SVGFOracle::atrousLevel(const SVGFOracleParams& p, int w, int h,
                                            const std::vector<double>& in,
                                            const std::vector<float>& normal,
                                            const std::vector<float>& depth,
                                            const std::vector<char>& hasData, int level) {
    std::vector<double> out(in);
    const int step = 1 << level;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            const double zp = depthAt(depth, w, x, y);
            if (zp <= 0.0) continue;  // miss: passes through
            double g[2];
            depthGradient(depth, w, h, x, y, zp, g);
            const double lp = luminance709(&in[i * 4]);
            double var = 0.0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int qx = std::clamp(x + dx, 0, w - 1), qy = std::clamp(y + dy, 0, h - 1);
                    const double k = (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
                    var += k * in[(size_t(qy) * size_t(w) + size_t(qx)) * 4 + 3];
                }
            const double wc = hasData[i] ? kB3[0] * kB3[0] : 0.0;
            double sum[3] = {wc * in[i * 4], wc * in[i * 4 + 1], wc * in[i * 4 + 2]};
            double sumV = wc * wc * in[i * 4 + 3], sumW = wc;
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx) {
                    if (dx == 0 && dy == 0) continue;
                    const int qx = x + step * dx, qy = y + step * dy;
                    if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
                    const size_t q = size_t(qy) * size_t(w) + size_t(qx);
                    const double zq = depthAt(depth, w, qx, qy);
                    if (zq <= 0.0 || !hasData[q]) continue;
                    const double wgt =
                        kB3[std::abs(dx)] * kB3[std::abs(dy)] *
                        depthWeight(zp, zq, g, step * dx, step * dy, p.sigmaDepth) *
                        normalWeight(&normal[i * 4], &normal[q * 4], p.sigmaNormal) *
                        std::exp(
                            -std::fabs(lp - luminance709(&in[q * 4])) /
                            (p.sigmaLuminance * std::sqrt(std::max(std::max(var, 0.0),
                                                                   std::max(in[q * 4 + 3], 0.0))) +
                             1e-10));
                    for (int c = 0; c < 3; ++c) sum[c] += wgt * in[q * 4 + size_t(c)];
                    sumV += wgt * wgt * in[q * 4 + 3];
                    sumW += wgt;
                }
            if (sumW > 0.0) {
                for (int c = 0; c < 3; ++c) out[i * 4 + size_t(c)] = sum[c] / sumW;
                out[i * 4 + 3] = sumV / (sumW * sumW);
            }
        }
    return out;
}

void SVGFOracle::frame(const SVGFOracleFrame& f, bool history) {
    const int w = f.width, h = f.height;
    const size_t n = size_t(w) * size_t(h);
    const auto& color = *f.color;
    const auto& depth = *f.depth;
    const auto& normal = *f.normal;
    if (mHistLength.size() != n) {
        history = false;
        mHistColor.assign(n * 4, 0.0);
        mHistMoments.assign(n * 2, 0.0);
        mHistLength.assign(n, 0.0);
    }
    // §4.1 temporal accumulation (still camera: the only tap is the pixel itself).
    std::vector<double> moments(n * 2), length(n);
    mAccumulated.assign(n * 4, 0.0);
    std::vector<char> hit(n), hasData(n);
    for (size_t i = 0; i < n; ++i) {
        const double z = depth[i * 4];
        hit[i] = z > 0.0;
        const bool sampled = color[i * 4 + 3] > 0.0;
        double x[3];
        for (int c = 0; c < 3; ++c) x[c] = std::clamp(double(color[i * 4 + size_t(c)]), 0.0, 1e15);
        const double l = luminance709(x);
        const bool valid = hit[i] && history && mHistLength[i] > 0.0;
        double C[3], M[2], hl;
        if (valid && sampled) {
            hl = std::min(mHistLength[i] + 1.0, mP.maxHistory);
            const double a = std::max(mP.alpha, 1.0 / hl), am = std::max(mP.momentsAlpha, 1.0 / hl);
            for (int c = 0; c < 3; ++c) C[c] = mHistColor[i * 4 + size_t(c)] * (1 - a) + x[c] * a;
            M[0] = mHistMoments[i * 2] * (1 - am) + l * am;
            M[1] = mHistMoments[i * 2 + 1] * (1 - am) + l * l * am;
        } else if (valid) {
            hl = mHistLength[i];
            for (int c = 0; c < 3; ++c) C[c] = mHistColor[i * 4 + size_t(c)];
            M[0] = mHistMoments[i * 2];
            M[1] = mHistMoments[i * 2 + 1];
        } else if (sampled) {
            hl = 1.0;
            for (int c = 0; c < 3; ++c) C[c] = x[c];
            M[0] = l;
            M[1] = l * l;
        } else {
            hl = 0.0;
            C[0] = C[1] = C[2] = M[0] = M[1] = 0.0;
        }
        if (!hit[i]) hl = 0.0;
        for (int c = 0; c < 3; ++c) mAccumulated[i * 4 + size_t(c)] = C[c];
        mAccumulated[i * 4 + 3] = hl;
        moments[i * 2] = M[0];
        moments[i * 2 + 1] = M[1];
        length[i] = hl;
        hasData[i] = hl > 0.0;
    }
    // §4.2 variance.
    std::vector<double> cur(n * 4);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            double C[3] = {mAccumulated[i * 4], mAccumulated[i * 4 + 1], mAccumulated[i * 4 + 2]};
            double m[2] = {moments[i * 2], moments[i * 2 + 1]};
            const double hl = length[i];
            const double zp = depthAt(depth, w, x, y);
            if (hl <= 0.0 || zp <= 0.0) {
                for (int c = 0; c < 3; ++c) cur[i * 4 + size_t(c)] = C[c];
                cur[i * 4 + 3] = 0.0;
                continue;
            }
            if (hl < mP.historyForVariance) {
                double g[2];
                depthGradient(depth, w, h, x, y, zp, g);
                double sC[3] = {0, 0, 0}, sM[2] = {0, 0}, sW = 0.0;
                const int r = mP.spatialRadius;
                for (int dy = -r; dy <= r; ++dy)
                    for (int dx = -r; dx <= r; ++dx) {
                        const int qx = x + dx, qy = y + dy;
                        if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
                        const size_t q = size_t(qy) * size_t(w) + size_t(qx);
                        const double zq = depthAt(depth, w, qx, qy);
                        if (length[q] <= 0.0 || zq <= 0.0) continue;
                        double wgt = 1.0;
                        if (dx != 0 || dy != 0)
                            wgt = depthWeight(zp, zq, g, dx, dy, mP.sigmaDepth) *
                                  normalWeight(&normal[i * 4], &normal[q * 4], mP.sigmaNormal);
                        for (int c = 0; c < 3; ++c) sC[c] += wgt * mAccumulated[q * 4 + size_t(c)];
                        sM[0] += wgt * moments[q * 2];
                        sM[1] += wgt * moments[q * 2 + 1];
                        sW += wgt;
                    }
                for (int c = 0; c < 3; ++c) C[c] = sC[c] / sW;
                m[0] = sM[0] / sW;
                m[1] = sM[1] / sW;
            }
            double var = std::max(m[1] - m[0] * m[0], 0.0);
            if (hl < mP.historyForVariance) var *= 4.0 / hl;
            for (int c = 0; c < 3; ++c) cur[i * 4 + size_t(c)] = C[c];
            cur[i * 4 + 3] = var;
        }
    // §4.3 a-trous levels; the output of level feedbackTap becomes the colour history.
    std::vector<double> newHist = mAccumulated;
    for (int level = 0; level < mP.iterations; ++level) {
        cur = atrousLevel(mP, w, h, cur, normal, depth, hasData, level);
        if (level + 1 == mP.feedbackTap) newHist = cur;
    }
    mHistColor = newHist;
    mHistMoments = moments;
    mHistLength = length;
    mIllumination = cur;
    mFiltered.assign(n * 4, 1.0);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            const size_t k = i * 4 + size_t(c);
            double a = 1.0, le = 0.0;
            if (f.albedo && (*f.albedo)[k] > 1e-3) a = (*f.albedo)[k];
            if (f.emission) le = (*f.emission)[k];
            mFiltered[k] = cur[k] * a + le;
        }
}

}  // namespace fovea::testsvgf
