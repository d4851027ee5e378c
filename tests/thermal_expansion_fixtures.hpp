// Shared set-up of the thermal-expansion tests of the ordinary models (test_thermal_expansion.cpp,
// test_thermal_expansion_forces.cpp): the steel and heating, the 20-node bar, a uniformly scaled body,
// the largest nodal norm, the comparison of two force fields and of the chunk path with the per-node
// path, and the models (PMB, LPS, LPS+SCF, PALS) with or without thermal expansion.
#pragma once

#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
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
// The chunk path (bonds without damage) against the per-node path (the same bonds with damage enabled
// and none broken) at y: for_each(bonds, fn) calls fn(name, model) for each model on those bonds; the
// same terms summed in another order, so equal to 1e-12 of the largest force.
template <class ForEach>
void expect_chunk_path_matches_per_node(const Body<3>& body, const Field<3>& y, ForEach&& for_each)
{
    Bonds chunked = build_bonds(body, 3 * dx), per_node = chunked;
    per_node.enable_damage();
    std::vector<Field<3>> ref;
    for_each(per_node, [&](const char*, auto& model) { internal_force(model, per_node, y, ref.emplace_back()); });
    int q = 0;
    for_each(chunked, [&](const char* name, auto& model) {
#ifdef PD_CHUNK_WIDTH
        ASSERT_FALSE(model.runs.chunk_start.empty()) << name << ": no chunks on this bar";
#endif
        Field<3> f;
        internal_force(model, chunked, y, f);
        expect_forces_near(f, ref[q++], 1e-12, name);
    });
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
