// Shared set-up of the correspondence thermal-expansion tests (test_correspondence_thermal.cpp,
// test_correspondence_thermal_rate.cpp): the steel and heating, the 16-node block, a uniformly scaled
// body and the largest deviation of the nodal stresses from s I.
#pragma once

#include "pd/core/lattice.hpp"
#include "pd/models/correspondence.hpp"

#include <algorithm>
#include <cstddef>

namespace pd_test::correspondence_thermal_fixtures {

using namespace pd;

inline constexpr double dx = 1e-3, alpha = 1.2e-5, theta_ref = 293.15, heat = 50;  // [m], [1/K], [K], [K]
inline const Elastic mat = Elastic::from_E_nu(200e9, 0.25);
using C3 = Correspondence<3>;

inline Body<3> block() { return box<3>({{0, 0, 0}}, {{16 * dx, 5 * dx, 4 * dx}}, dx); }

template <int D>
Field<D> scaled(const Body<D>& body, double s)
{
    Field<D> y = body.x;
    for (int d = 0; d < D; ++d) for (auto& v : y.c[d]) v *= s;
    return y;
}
// Largest entry of |sigma_i - s I| over the nodes with a regular shape tensor [Pa].
template <class Mats, class Model>
double max_off(const Mats& sigma, const Model& m, double s)
{
    double e = 0;
    for (std::size_t i = 0; i < sigma.size(); ++i) {
        if (m.Kinv[i].isZero(0)) continue;
        auto d = sigma[i];
        d.diagonal().array() -= s;
        e = std::max(e, d.cwiseAbs().maxCoeff());
    }
    return e;
}

}  // namespace pd_test::correspondence_thermal_fixtures
