// A model's force at y against minus the gradient of its energy E = sum_i W_i V_i, by central
// differences of step h [m] at the given nodes: |f_d V_i + dE/dy_d| <= tol |f_i V_i| for each
// component d (a small component alone can lose digits, so the node's whole force sets the scale).
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/core/lattice.hpp"

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

namespace pd_test {

template <class Model>
void expect_force_is_energy_gradient(Model& model, const pd::Bonds& b, const pd::Body<3>& body, const pd::Field<3>& y,
                                     std::initializer_list<int> nodes, double h, double tol, const std::string& label)
{
    auto total = [&](const pd::Field<3>& yy) {
        if constexpr (Model::has_point_pass) model.point_pass(b, yy);
        const auto W = model.energy_density(b, yy);
        double E = 0;
        for (std::size_t i = 0; i < body.size(); ++i) E += W[i] * body.volume[i];
        return E;
    };
    pd::Field<3> f;
    pd::internal_force(model, b, y, f);
    for (int node : nodes) {
        const double scale = norm(f[node]) * body.volume[node];
        for (int d = 0; d < 3; ++d) {
            pd::Field<3> yp = y, ym = y;
            yp.c[d][node] += h;
            ym.c[d][node] -= h;
            const double dE = (total(yp) - total(ym)) / (2 * h);
            EXPECT_NEAR(-f.c[d][node] * body.volume[node], dE, tol * scale) << label << " node " << node << " dir " << d;
        }
    }
}

}  // namespace pd_test
