#include "core/shading/SpecularAlbedo.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <numbers>

namespace fovea::shading {
namespace {

constexpr double kPi = std::numbers::pi;

double alphaOf(double roughness) {
    return std::max(roughness * roughness, kSpecularMinAlpha);
}

// Smith Lambda for GGX (brdf.glsl brdfLambda); c >= kSpecularMinCos.
double lambda(double c, double a) {
    const double t2 = std::max(0.0, 1.0 - c * c) / (c * c);
    return 0.5 * (std::sqrt(1.0 + a * a * t2) - 1.0);
}

double ggxD(double nh, double a) {
    const double a2 = a * a;
    const double d = nh * nh * (a2 - 1.0) + 1.0;
    return a2 / (kPi * d * d);
}

double fresnelWeight(double voh) {  // (1 - VoH)^5 of Schlick's F = F0 + (1 - F0) (1 - VoH)^5
    const double k = 1.0 - std::clamp(voh, 0.0, 1.0);
    return k * k * k * k * k;
}

glm::dvec3 viewDirection(double nov) {
    const double mu = std::clamp(nov, kSpecularMinCos, 1.0);
    return {std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu};
}

// Heitz 2018, "Sampling the GGX Distribution of Visible Normals", in the normal's frame (z up).
glm::dvec3 sampleVisibleNormal(const glm::dvec3& wo, double a, double u1, double u2) {
    const glm::dvec3 vh = glm::normalize(glm::dvec3(a * wo.x, a * wo.y, wo.z));
    const double lensq = vh.x * vh.x + vh.y * vh.y;
    const glm::dvec3 t1 =
        lensq > 0.0 ? glm::dvec3(-vh.y, vh.x, 0.0) / std::sqrt(lensq) : glm::dvec3(1, 0, 0);
    const glm::dvec3 t2 = glm::cross(vh, t1);
    const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
    const double p1 = r * std::cos(phi);
    double p2 = r * std::sin(phi);
    const double s = 0.5 * (1.0 + vh.z);
    p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * p2;
    const glm::dvec3 nh =
        p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(glm::dvec3(a * nh.x, a * nh.y, std::max(0.0, nh.z)));
}

}  // namespace

glm::dvec2 integrateSpecularAlbedo(double nov, double roughness, int n) {
    const glm::dvec3 wo = viewDirection(nov);
    const double a = alphaOf(roughness);
    const double g1 = 1.0 / (1.0 + lambda(wo.z, a));
    glm::dvec2 sum(0.0);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const glm::dvec3 h = sampleVisibleNormal(wo, a, (x + 0.5) / n, (y + 0.5) / n);
            const double voh = glm::dot(wo, h);
            const glm::dvec3 wi = 2.0 * voh * h - wo;
            if (wi.z <= 0.0) continue;  // reflected below the surface: f cos = 0 there
            const double g2 =
                1.0 / (1.0 + lambda(wo.z, a) + lambda(std::max(wi.z, kSpecularMinCos), a));
            const double w = g2 / g1;  // F G2 / G1(wo) with F split into its two parts
            const double fc = fresnelWeight(glm::dot(h, wi));
            sum += glm::dvec2((1.0 - fc) * w, fc * w);
        }
    return sum / double(n * n);
}

glm::dvec2 integrateSpecularAlbedoQuadrature(double nov, double roughness, int thetaSteps,
                                             int phiSteps) {
    const glm::dvec3 wo = viewDirection(nov);
    const double a = alphaOf(roughness);
    glm::dvec2 sum(0.0);
    const double dTheta = 0.5 * kPi / thetaSteps, dPhi = 2.0 * kPi / phiSteps;
    for (int t = 0; t < thetaSteps; ++t) {
        const double theta = (t + 0.5) * dTheta;
        const double ct = std::cos(theta), st = std::sin(theta);
        for (int p = 0; p < phiSteps; ++p) {
            const double phi = (p + 0.5) * dPhi;
            const glm::dvec3 wi(st * std::cos(phi), st * std::sin(phi), ct);
            const glm::dvec3 h = glm::normalize(wo + wi);  // wo, wi both above: never zero
            const double nl = std::max(ct, kSpecularMinCos);
            const double g2 = 1.0 / (1.0 + lambda(wo.z, a) + lambda(nl, a));
            // f_spec / F = D G2 / (4 NoV NoL); times cos theta_i and the cell's solid angle.
            const double f = ggxD(h.z, a) * g2 / (4.0 * wo.z * nl);
            const double weight = f * ct * st * dTheta * dPhi;
            const double fc = fresnelWeight(glm::dot(h, wi));
            sum += glm::dvec2((1.0 - fc) * weight, fc * weight);
        }
    }
    return sum;
}

std::vector<glm::vec2> specularAlbedoTable() {
    const int n = kSpecularAlbedoSize;
    std::vector<glm::vec2> table(size_t(n * n));
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            table[size_t(j * n + i)] =
                glm::vec2(integrateSpecularAlbedo(double(i) / (n - 1), double(j) / (n - 1)));
    return table;
}

glm::dvec2 lookupSpecularAlbedo(const std::vector<glm::vec2>& table, double nov, double roughness) {
    const int n = kSpecularAlbedoSize;
    // NaN compares false: it reads as 0, as in the shader.
    const double x = (nov > 0.0 ? std::min(nov, 1.0) : 0.0) * (n - 1);
    const double y = (roughness > 0.0 ? std::min(roughness, 1.0) : 0.0) * (n - 1);
    const int x0 = std::min(int(x), n - 2), y0 = std::min(int(y), n - 2);
    const double fx = x - x0, fy = y - y0;
    auto at = [&](int i, int j) { return glm::dvec2(table.at(size_t(j * n + i))); };
    const glm::dvec2 lo = at(x0, y0) * (1.0 - fx) + at(x0 + 1, y0) * fx;
    const glm::dvec2 hi = at(x0, y0 + 1) * (1.0 - fx) + at(x0 + 1, y0 + 1) * fx;
    return lo * (1.0 - fy) + hi * fy;
}

const std::vector<glm::vec2>& bakedSpecularAlbedoTable() {
    static const std::vector<glm::vec2> kTable = {
#include "core/shading/SpecularAlbedoTable.inc"
    };
    return kTable;
}

std::string specularAlbedoTableSource(const std::vector<glm::vec2>& table) {
    const int n = kSpecularAlbedoSize;
    std::string s =
        "// GENERATED by core/shading/SpecularAlbedo.cpp specularAlbedoTableSource(); do not "
        "edit.\n"
        "// Regenerate: FOVEA_UPDATE_TABLES=1 build/tests/fovea_tests "
        "--gtest_filter='SpecularAlbedo.*'\n"
        "// {scale, bias} of E(F0, roughness, NoV) = F0 * scale + bias (SpecularAlbedo.h), " +
        std::to_string(n) + " x " + std::to_string(n) + " entries,\n// NoV = i / " +
        std::to_string(n - 1) + " along a row, roughness = j / " + std::to_string(n - 1) +
        " down the rows.\n";
    char buf[64];
    for (int j = 0; j < n; ++j) {
        s += "// roughness " + std::to_string(j) + " / " + std::to_string(n - 1) + "\n";
        for (int i = 0; i < n; ++i) {
            const glm::vec2& t = table[size_t(j * n + i)];
            std::snprintf(buf, sizeof buf, "{%#.9gf, %#.9gf},", double(t.x), double(t.y));
            s += std::string(i % 2 == 0 ? "" : " ") + buf + (i % 2 == 1 ? "\n" : "");
        }
    }
    return s;
}

}  // namespace fovea::shading
