// Shared set-up of the k(theta) tests (test_heat_conductivity.cpp, test_heat_conductivity_steady.cpp):
// the linear law, the 1D bar with held layers, and Agwai and correspondence heat wrapped for k(theta).
#pragma once

#include "pd/heat/agwai.hpp"
#include "pd/heat/conductivity.hpp"
#include "pd/heat/correspondence_heat.hpp"
#include "pd/core/lattice.hpp"

#include <cstddef>

namespace pd_test::heat_conductivity_fixtures {

// Linear law k = k0 (1 + beta (T - T0)) [W/(m K)]: steel-like, k falls by 40 % from 0 to 800 C.
inline constexpr double k0 = 50, beta = -5e-4, Tk = 0;
inline pd::Property linear_k() { return pd::Property::piecewise({{-1e4, 1e4, [](double T) { return k0 * (1 + beta * (T - Tk)); }}}); }

// 1D bar [0, L] of N cells, held layers of m cells outside each end, full volumes.
struct Bar {
    static constexpr double L = 0.1, A = 1e-4, rho_c = 7850 * 600.0;  // [m], [m^2], [J/(m^3 K)]
    static constexpr int m = 3;
    int N;
    double dx = L / N;
    pd::Body<1> body = pd::box<1>(pd::Vec<1>{-m * dx}, pd::Vec<1>{L + m * dx}, dx, A);
    pd::Bonds bonds = pd::build_bonds(body, m * dx);
    explicit Bar(int n) : N(n) {}
    bool outside(std::size_t i) const { return body.x.c[0][i] < 0 || body.x.c[0][i] > L; }
};

using AgwaiK = pd::ConductivityOfTheta<pd::Agwai>;
using CorrK = pd::ConductivityOfTheta<pd::CorrespondenceHeat<1>>;
inline const AgwaiK::Params agwai_params{0, Bar::A};
inline const CorrK::Params corr_params{0, 1.0, Bar::A};  // C_hg = 1: without it the odd-even mode makes the steady problem singular

}  // namespace pd_test::heat_conductivity_fixtures
