#include "tests/graph/BMFROracle.h"

#include <Eigen/Dense>

namespace fovea::testref {

BMFRBlockFit bmfrOracleFit(const BMFRBlockInput& in) {
    const Eigen::Index n = Eigen::Index(in.target.size() / 3);
    const bool albedo = !in.albedo.empty();
    const Eigen::Index m = albedo ? 13 : 10;
    BMFRBlockFit out;
    out.fitted.assign(size_t(n) * 3, 0.0);
    if (n == 0) return out;

    double mean[3] = {0, 0, 0};
    for (Eigen::Index i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) mean[c] += in.position[size_t(i) * 3 + c] / double(n);

    Eigen::MatrixXd t(n, m);
    Eigen::MatrixXd z(n, 3);
    for (Eigen::Index i = 0; i < n; ++i) {
        const size_t k = size_t(i) * 3;
        t(i, 0) = 1.0;
        for (int c = 0; c < 3; ++c) {
            const double w = in.position[k + c] - mean[c];
            t(i, 1 + c) = in.normal[k + c];
            t(i, 4 + c) = w;
            t(i, 7 + c) = w * w;
            if (albedo) t(i, 10 + c) = in.albedo[k + c];
            z(i, c) = in.target[k + c];
        }
    }
    // Column scaling keeps the rank decision independent of units.
    Eigen::VectorXd scale(m);
    for (Eigen::Index j = 0; j < m; ++j) {
        const double s = t.col(j).cwiseAbs().maxCoeff();
        scale(j) = s > 0 ? 1.0 / s : 0.0;
    }
    const Eigen::MatrixXd ts = t * scale.asDiagonal();
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(ts);
    cod.setThreshold(1e-9);
    const Eigen::MatrixXd coef = cod.solve(z);
    const Eigen::MatrixXd y = ts * coef;
    out.rank = int(cod.rank());
    for (Eigen::Index i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            out.fitted[size_t(i) * 3 + c] = y(i, c);
            const double r = z(i, c) - y(i, c);
            out.residual2[c] += r * r;
        }
    return out;
}

}  // namespace fovea::testref
