// pd/core/mls.hpp -- moving least squares with a linear basis: the weights that carry nodal values
// (displacement, velocity, acceleration) onto a new point, for the nodes adaptive refinement creates
// (spec/002 sec. 4.8; V6c). At the point z, with p(x) = [1, x - z] and weights w_j = (1 - (r_j/R)^2)^2
// of the support nodes (distance r_j < R):
//   A = sum_j w_j p(x_j) p(x_j)^T,   phi_j = w_j [A^-1 p(x_j)]_0,   f(z) = sum_j phi_j f_j,
// the value at z of the weighted least-squares linear fit, so any linear field is reproduced exactly
// (sum phi_j = 1, sum phi_j (x_j - z) = 0). The caller chooses the support: for a child of a split
// node, the parent and its partners over intact bonds, so no value is carried across a crack.
// A support that does not span D dimensions (A singular to 1e-12 relative) gives the weights of the
// support node nearest z alone (a constant): the caller loses linear exactness there, not the run.
#pragma once
#include "pd/core/field.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace pd {

// phi_j of the support nodes (indices into x) at z, with radius R [m] (> every distance used).
template <int D>
std::vector<double> mls_weights(const Field<D>& x, const std::vector<int>& support, const Vec<D>& z, double R)
{
    using Mat = Eigen::Matrix<double, D + 1, D + 1>;
    using Col = Eigen::Matrix<double, D + 1, 1>;
    if (support.empty()) throw std::invalid_argument("mls_weights: empty support");
    if (!(R > 0)) throw std::invalid_argument("mls_weights: the radius must be positive");
    Mat A = Mat::Zero();
    std::vector<Col> p(support.size());
    std::vector<double> w(support.size());
    std::size_t nearest = 0;
    for (std::size_t q = 0; q < support.size(); ++q) {
        const Vec<D> d = x[support[q]] - z;
        const double r = norm(d);
        if (r >= R) throw std::invalid_argument("mls_weights: a support node lies beyond the radius");
        const double s = 1 - (r / R) * (r / R);
        w[q] = s * s;
        p[q](0) = 1;
        for (int k = 0; k < D; ++k) p[q](k + 1) = d[k] / R;  // scaled by R: A is O(1)
        A += w[q] * p[q] * p[q].transpose();
        if (r < norm(x[support[nearest]] - z)) nearest = q;
    }
    std::vector<double> phi(support.size(), 0.0);
    Eigen::FullPivLU<Mat> lu(A);
    lu.setThreshold(1e-12);
    if (!lu.isInvertible()) {
        phi[nearest] = 1;
        return phi;
    }
    for (std::size_t q = 0; q < support.size(); ++q) phi[q] = w[q] * lu.solve(p[q])(0);
    return phi;
}

}  // namespace pd
