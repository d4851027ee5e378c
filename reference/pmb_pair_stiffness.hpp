// reference/pmb_pair_stiffness.hpp -- the stiffness matrix of linearised PMB written out pair by
// pair, independent of the peridynamics library (the reference of the finite-difference assembly
// in problems/common/analysis/stiffness_matrix.hpp, problems/3d/hourglass_modes.cpp and its test).
//
// PMB pair springs (Silling & Askari 2005), linearised at the reference configuration, influence
// omega = 1: the force on i from j is c V_i V_j ((u_j - u_i).n / |xi|) n, n = xi/|xi|, xi = x_j - x_i,
// so the 3x3 blocks are K_ij = -c V_i V_j n n^T / |xi| and K_ii = -sum_j K_ij [N/m]; c = 18 K /
// (pi delta^4) in 3D (spec/000b V12). Pairs with |xi| <= delta (1 + 1e-10), the horizon rule of
// pd::build_bonds; full nodal volumes (no partial-volume factor).
#pragma once

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <vector>

namespace pd::ref {

// x: coordinates x[d][i] [m]; V: nodal volumes [m^3]; delta: horizon [m]; c: micromodulus [N/m^6].
inline Eigen::MatrixXd pmb_pair_stiffness(const std::array<std::vector<double>, 3>& x, const std::vector<double>& V, double delta,
                                          double c)
{
    const int N = static_cast<int>(V.size());
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(3 * N, 3 * N);
    for (int i = 0; i < N; ++i)
        for (int j = 0; j < N; ++j) {
            double xi[3], r2 = 0;
            for (int a = 0; a < 3; ++a) xi[a] = x[a][j] - x[a][i], r2 += xi[a] * xi[a];
            const double r = std::sqrt(r2);
            if (i == j || r > delta * (1 + 1e-10)) continue;
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) {
                    const double k = c * V[i] * V[j] * xi[a] * xi[b] / (r * r * r);
                    K(3 * i + a, 3 * j + b) -= k;
                    K(3 * i + a, 3 * i + b) += k;
                }
        }
    return K;
}

}  // namespace pd::ref
