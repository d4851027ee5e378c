// Shared set-up of the thermal-expansion tests of the ordinary models (test_thermal_expansion.cpp,
// test_thermal_expansion_forces.cpp): the steel and heating, the 20-node bar, a uniformly scaled body,
// the largest nodal norm and the models (PMB, LPS, LPS+SCF, PALS) with or without thermal expansion.
#pragma once

#include "pd/core/lattice.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/pmb.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

namespace pd_test::thermal_expansion_fixtures {

using namespace pd;

inline constexpr double dx = 1e-3, alpha = 1.2e-5, theta_ref = 293.15, heat = 50;  // [m], [1/K], [K], [K]
inline const Elastic mat = Elastic::from_E_nu(200e9, 0.25);

inline Body<3> bar() { return box<3>({{0, 0, 0}}, {{20 * dx, 5 * dx, 4 * dx}}, dx); }

template <int D>
Field<D> scaled(const Body<D>& body, double s)
{
    Field<D> y = body.x;
    for (int d = 0; d < D; ++d) for (auto& v : y.c[d]) v *= s;
    return y;
}
inline double max_norm(const Field<3>& f)
{
    double m = 0;
    for (std::size_t i = 0; i < f.size(); ++i) m = std::max(m, norm(f[i]));
    return m;
}
// |f_i - ref_i| <= rel max_i |ref_i| at every node (label names the model).
inline void expect_forces_near(const Field<3>& f, const Field<3>& ref, double rel, const std::string& label)
{
    const double scale = max_norm(ref);
    for (std::size_t i = 0; i < f.size(); ++i) EXPECT_LE(norm(f[i] - ref[i]), rel * scale) << label << " node " << i;
}
// The models on b, each with thermal expansion from theta (null: none): PMB, LPS (intact and
// reference weighted volume), LPS+SCF and PALS.
template <class Fn>
void for_each_model(const Bonds& b, const Body<3>& body, const std::vector<double>* theta, Fn&& fn)
{
    const ThermalExpansion t{alpha, theta_ref, theta};
    PMB pmb({mat, 3}, b);
    LPS lps({mat, 3}, b), scf({mat, 3}, b), ref({mat, 3, Plane::strain, LPS::Params::WeightedVolume::reference}, b);
    PALS pals({.material = mat}, body, b);
    scf.apply_shear_correction(body.x);
    if (theta) pmb.set_thermal_expansion(t), lps.set_thermal_expansion(t), scf.set_thermal_expansion(t), ref.set_thermal_expansion(t);
    if (theta) pals.set_thermal_expansion(t);
    fn("PMB", pmb);
    fn("LPS", lps);
    fn("LPS+SCF", scf);
    fn("LPS reference m", ref);
    fn("PALS", pals);
}

}  // namespace pd_test::thermal_expansion_fixtures
