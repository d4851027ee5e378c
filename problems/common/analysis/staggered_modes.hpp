// problems/common/analysis/staggered_modes.hpp -- test fields for zero-energy (hourglass) mode studies on a
// lattice patch (problems/3d/hourglass_modes.cpp; spec/000a sec. 2.7-2.8): the staggered patterns
// (-1)^(k.a) of the lattice index a, k in {0, 1}^D, plain or under the bubble envelope
// phi = prod_d sin(pi x_d / L), and the energy density they cost at the nodes with a full family.
#pragma once

#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/core/lattice.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace pd {

// Test fields with the staggering (-1)^(k.a) of lattice index a = (a, b, c) and a wave-vector mask
// k in {0, 1}^D (k pi / dx), polarised along e_pol: kind 0 plain, kind 1 times the bubble envelope
// phi = prod_d sin(pi x_d / L) (vanishing at the free faces), kind 2 phi alone (k ignored: a
// long-wave elastic mode, the physical scale). The checkerboard is k = (1, 1, 1), pol = x.
template <int D>
Eigen::VectorXd staggered_pattern(const Body<D>& body, double L, int kind, int k_mask = 7, int pol = 0)
{
    Eigen::VectorXd u = Eigen::VectorXd::Zero(D * body.size());
    for (std::size_t i = 0; i < body.size(); ++i) {
        long parity = 0;
        double phi = 1;
        for (int d = 0; d < D; ++d) {
            if (k_mask >> d & 1) parity += std::lround(body.x.c[d][i] / body.dx - 0.5);
            phi *= std::sin(std::numbers::pi * body.x.c[d][i] / L);
        }
        const double sign = parity % 2 ? -1 : 1;
        u(D * i + pol) = kind == 0 ? sign : kind == 1 ? sign * phi : phi;
    }
    return u;
}

// Energy density of the checkerboard (amplitude 1e-6 dx) at the nodes with a full family, whose
// neighbours all sit symmetrically: max W / (E (a/dx)^2 / 2). NaN when no node has a full family.
// Correspondence: W excludes the hourglass energy (correspondence.hpp).
template <int D, class Model>
double interior_checker_energy(Model& model, const Body<D>& body, const Bonds& bonds, double E)
{
    if (!families_within_horizon(bonds))
        throw std::invalid_argument("interior_checker_energy: full families are counted within delta; these reach beyond it (exact-area)");
    const std::int64_t full = static_cast<std::int64_t>(full_family_offsets(bonds.delta, body.dx, D).size());
    const double a = 1e-6 * body.dx;  // amplitude [m]
    const Eigen::VectorXd u = staggered_pattern(body, 1.0, 0);
    Field<D> y = body.x, f;
    for (std::size_t i = 0; i < body.size(); ++i) y.c[0][i] += a * u(D * i);
    internal_force(model, bonds, y, f);  // point pass at y (theta, F)
    const std::vector<double> W = model.energy_density(bonds, y);
    double w = -1;
    for (std::size_t i = 0; i < body.size(); ++i)
        if (bonds.end(i) - bonds.begin(i) == full) w = std::max(w, std::abs(W[i]));
    return w < 0 ? NAN : w / (0.5 * E * (a / body.dx) * (a / body.dx));
}

}  // namespace pd
