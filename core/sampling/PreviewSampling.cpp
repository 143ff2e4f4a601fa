#include "core/sampling/PreviewSampling.h"

#include <algorithm>
#include <cmath>

#include "core/sampling/VisualPolar.h"

namespace fovea::sampling {

double acuityInversePublished(double u) {
    u = std::clamp(u, 0.0, 1.0);
    // The polynomial branch is P5 Eq. 3, the same fit (VisualPolar.h).
    return u <= 0.0965 ? 18.64 * std::sqrt(u) : acuityInversePolynomial(u);
}

InverseError publishedInverseError(int steps) {
    InverseError r;
    steps = std::max(steps, 2);
    double sumDiff = 0, sumExact = 0;
    const double du = 1.0 / steps;
    for (int i = 1; i <= steps; ++i) {
        const double u = i * du;
        const double exact = acuityInverse(u), published = acuityInversePublished(u);
        const double diff = std::abs(published - exact);
        const double rel = diff / exact;  // exact > 0 for u > 0
        if (rel > r.maxRelative) {
            r.maxRelative = rel;
            r.atU = u;
        }
        r.maxDegrees = std::max(r.maxDegrees, diff);
        sumDiff += diff * du;
        sumExact += exact * du;
        // Densities as 1 / (de/du) by central differences, on the polynomial branch only (the
        // square-root branch is exact; its derivative is unbounded at 0). The exact inverse
        // itself steps by 0.008 degrees at f(5.79), where P5 Eq. 2's rounded constants (166.4,
        // 612.3) leave the two branches of h 0.26 % apart: differences across it are skipped.
        if (u - du > std::max(0.0965, acuityCdf(kAcuityFlatDegrees)) && u < 1.0 - du) {
            const double dp = (acuityInversePublished(u + du) - acuityInversePublished(u - du));
            const double de = (acuityInverse(u + du) - acuityInverse(u - du));
            // Both inverses increase strictly (dp, de > 0); the density ratio is de / dp.
            r.maxDensityRelative = std::max(r.maxDensityRelative, std::abs(de / dp - 1.0));
        }
    }
    r.integralRelative = sumDiff / sumExact;
    return r;
}

}  // namespace fovea::sampling
