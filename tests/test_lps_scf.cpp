// LPS with the shear correction factor (models/lps.hpp, models/scf.hpp; spec/000b sec. 1.3, V12):
// pure-shear energy at a bulk node against the classical value, SCF = 1 bit-identical to no
// correction, and the force as the energy gradient under a non-uniform SCF.
#include "pd/bond_loop.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/scf.hpp"

#include <gtest/gtest.h>

#include "energy_gradient.hpp"
#include "scf_fixtures.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

using namespace pd;
using namespace pd_test::scf_fixtures;

namespace {
template <int D>
Field<D> sheared(const Body<D>& body, int a, int c, double g)  // y_a = x_a + g x_c, y_c = x_c + g x_a
{
    Field<D> y = body.x;
    for (std::size_t i = 0; i < body.size(); ++i) { y.c[a][i] += g * body.x.c[c][i]; y.c[c][i] += g * body.x.c[a][i]; }
    return y;
}
}  // namespace

// LPS with SCF under pure shear at a bulk node: classical W = G eps:eps = 2 G gamma^2 for
// eps_ab = eps_ba = gamma. Plain LPS gives 2 G gamma^2 / SCF_bulk (3D: 131/118 = 1.1102, 2D:
// 82/85 = 0.9647); with SCF it gives 2 G gamma^2 in all three coordinate shears (all equal on
// the cubic lattice by symmetry). The rotated shear diag(a, -a, 0) (classical also 2 G a^2) is a
// different cubic mode: ratio 15 T / (4 m) * SCF with T = sum (p^2 - q^2)^2 / |n|^2 = 157.6,
// 0.8347 plain and 0.7519 corrected: the SCF fixes the probed shear family, not the cubic
// anisotropy of the lattice. Tolerance 1e-5: O(gamma) nonlinearity, theta = O(gamma^2).
TEST(LPS_SCF, PureShearEnergyBecomesClassical)
{
    const double dx = 1e-3, g = 1e-6;
    const Elastic mat = Elastic::from_E_nu(200e9, 0.3);
    auto body = box<3>({{0, 0, 0}}, {{7 * dx, 7 * dx, 7 * dx}}, dx);
    Bonds b = build_bonds(body, 3 * dx);
    const int mid = 3 + 3 * 7 + 3 * 49;
    LPS plain({mat, 3}, b), corr({mat, 3}, b);
    corr.apply_shear_correction(body.x);
    const double W_cl = 2 * mat.G * g * g, scf_ref = lattice_scf<3>();
    const int modes[3][2] = {{0, 1}, {2, 0}, {1, 2}};
    for (const auto& md : modes) {
        const Field<3> y = sheared(body, md[0], md[1], g);
        plain.point_pass(b, y);
        corr.point_pass(b, y);
        EXPECT_NEAR(plain.energy_density(b, y)[mid] / W_cl, 1 / scf_ref, 1e-5);
        EXPECT_NEAR(corr.energy_density(b, y)[mid] / W_cl, 1.0, 1e-5);
    }
    Field<3> y = body.x;
    for (std::size_t i = 0; i < body.size(); ++i) { y.c[0][i] *= 1 + g; y.c[1][i] *= 1 - g; }
    plain.point_pass(b, y);
    corr.point_pass(b, y);
    const double T = 157.6, m = 708;  // lattice sums over the 122 offsets (cf. lattice_scf)
    EXPECT_NEAR(plain.energy_density(b, y)[mid] / W_cl, 15 * T / (4 * m), 1e-5);
    EXPECT_NEAR(corr.energy_density(b, y)[mid] / W_cl, 15 * T / (4 * m) * scf_ref, 1e-5);

    auto body2 = box<2>({{0, 0}}, {{7 * dx, 7 * dx}}, dx, 1e-3);
    Bonds b2 = build_bonds(body2, 3 * dx);
    LPS plain2({mat, 2, Plane::strain}, b2), corr2({mat, 2, Plane::strain}, b2);
    corr2.apply_shear_correction(body2.x);
    const Field<2> y2 = sheared(body2, 0, 1, g);
    plain2.point_pass(b2, y2);
    corr2.point_pass(b2, y2);
    EXPECT_NEAR(plain2.energy_density(b2, y2)[3 + 3 * 7] / W_cl, 82.0 / 85.0, 1e-5);
    EXPECT_NEAR(corr2.energy_density(b2, y2)[3 + 3 * 7] / W_cl, 1.0, 1e-5);
}

// Off is the old model: alpha is the old a_D G / m_i (written out here), and SCF = 1 everywhere
// gives bit-identical alpha, forces and energies.
TEST(LPS_SCF, UnitFactorIsBitIdenticalToNoCorrection)
{
    const double dx = 1e-3;
    auto body = fill<3>({{0, 0, 0}}, {{8 * dx, 7 * dx, 6 * dx}}, dx, in_ball<3>({{4 * dx, 3.5 * dx, 3 * dx}}, 3.6 * dx));
    Bonds b = build_bonds(body, 3.05 * dx);
    const Elastic mat = Elastic::from_E_nu(200e9, 0.3);
    LPS off({mat, 3}, b), one({mat, 3}, b);
    one.apply_shear_correction(std::vector<double>(body.size(), 1.0));
    EXPECT_TRUE(off.scf.empty());
    for (std::size_t i = 0; i < body.size(); ++i) EXPECT_EQ(off.alpha[i], 15.0 * mat.G * (1.0 / off.m[i]));
    EXPECT_EQ(off.alpha, one.alpha);
    std::mt19937 gen(11);
    std::uniform_real_distribution<double> U(-1e-5, 1e-5);
    Field<3> y = body.x;
    for (int d = 0; d < 3; ++d) for (auto& v : y.c[d]) v += U(gen);
    Field<3> f_off, f_one;
    internal_force(off, b, y, f_off);
    internal_force(one, b, y, f_one);
    for (int d = 0; d < 3; ++d) EXPECT_EQ(f_off.c[d], f_one.c[d]);
    EXPECT_EQ(off.energy_density(b, y), one.energy_density(b, y));
    EXPECT_THROW(one.apply_shear_correction(std::vector<double>(3, 1.0)), std::invalid_argument);
}

// With a non-uniform SCF the force is still minus the gradient of E = sum_i W_i V_i (alpha_i
// enters W_i and t_i alike): central differences at a corner and a bulk node of a small box.
// Tolerance 1e-6 of |f_i V_i| (a small component alone can lose digits): step h = 1e-9 m against
// displacements 1e-8 m; observed differences ~1e-8 with and without SCF.
TEST(LPS_SCF, ForceIsEnergyGradientWithNonUniformSCF)
{
    const double dx = 1e-3, h = 1e-9;
    auto body = box<3>({{0, 0, 0}}, {{6 * dx, 6 * dx, 6 * dx}}, dx);
    Bonds b = build_bonds(body, 3 * dx);
    const Elastic mat = Elastic::from_E_nu(200e9, 0.3);
    LPS lps({mat, 3}, b);
    lps.apply_shear_correction(body.x);
    std::mt19937 gen(5);
    std::uniform_real_distribution<double> U(-1e-8, 1e-8);
    Field<3> y = body.x;
    for (int d = 0; d < 3; ++d) for (auto& v : y.c[d]) v += U(gen);
    pd_test::expect_force_is_energy_gradient(lps, b, body, y, {0, 2 + 2 * 6 + 3 * 36}, h, 1e-6, "LPS+SCF");
}
