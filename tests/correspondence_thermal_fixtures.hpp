// Shared set-up of the correspondence thermal-expansion tests (test_correspondence_thermal.cpp,
// test_correspondence_thermal_rate.cpp): the steel and heating, the 16-node block, a uniformly scaled
// body and the largest deviation of the nodal stresses from s I. The steel, the heating and scaled
// are those of the ordinary models' tests (thermal_expansion_fixtures.hpp).
#pragma once

#include "pd/core/lattice.hpp"
#include "pd/models/correspondence.hpp"

#include "thermal_expansion_fixtures.hpp"

#include <algorithm>
#include <cstddef>

namespace pd_test::correspondence_thermal_fixtures {

using namespace pd;
using thermal_expansion_fixtures::alpha, thermal_expansion_fixtures::dx, thermal_expansion_fixtures::heat;
using thermal_expansion_fixtures::mat, thermal_expansion_fixtures::scaled, thermal_expansion_fixtures::theta_ref;
using C3 = Correspondence<3>;

inline Body<3> block() { return box<3>({{0, 0, 0}}, {{16 * dx, 5 * dx, 4 * dx}}, dx); }
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
