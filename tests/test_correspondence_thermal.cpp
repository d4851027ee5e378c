// Thermal expansion of the correspondence models (models/correspondence.hpp header; spec/000a
// eq. 2.81 and verification case V7), on a block long enough for the chunk path:
// - linear law: a free body at y = (1 + eps) x has sigma = 0 and no force at any node (surface nodes,
//   hourglass control and broken bonds included); a body held at y = x is under sigma = -3 K eps I in
//   3D and -E/(1 - nu) eps in 2D plane stress (the classical constrained thermal stress, V7);
// - J2 plasticity (PlasticCorrespondence): the same constrained stress while elastic, none when free;
// - theta = theta_ref is the isothermal result bit for bit; the refusals.
// (The rate forms, Flanagan-Taylor and the viscoelastic wrapper: test_correspondence_thermal_rate.cpp.)
#include "pd/bond_loop.hpp"
#include "pd/core/lattice.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/plastic_correspondence.hpp"

#include <gtest/gtest.h>

#include "correspondence_thermal_fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

using namespace pd;
using namespace pd_test::correspondence_thermal_fixtures;

namespace {
template <int D>
double max_norm(const Field<D>& f)
{
    double m = 0;
    for (std::size_t i = 0; i < f.size(); ++i) m = std::max(m, norm(f[i]));
    return m;
}
}  // namespace

TEST(CorrespondenceThermal, LinearFreeExpansionIsStressFree)
{
    const Body<3> body = block();
    const std::vector<double> theta(body.size(), theta_ref + heat);
    const double eps = alpha * heat, p = 3 * mat.K * eps;
    const Field<3> y = scaled(body, 1 + eps);
    for (bool damaged : {false, true})
        for (double C_hg : {0.0, 0.02}) {
            Bonds b = build_bonds(body, 3 * dx);
            if (damaged) {
                b.enable_damage();
                for (std::size_t k = 0; k < b.size(); k += 7) b.break_pair(static_cast<std::int64_t>(k));
            }
            C3 iso({.material = mat, .C_hg = C_hg}, body, b), th({.material = mat, .C_hg = C_hg}, body, b);
            th.set_thermal_expansion({alpha, theta_ref, &theta});
            Field<3> f_iso, f;
            internal_force(iso, b, y, f_iso);
            internal_force(th, b, y, f);
            const double scale = max_norm(f_iso);  // the isothermal forces of the same y
            ASSERT_GT(scale, 0);
            // F = (1 + eps) I to round-off (N K^-1 of the family sums), so both are round-off of F times K.
            EXPECT_LT(max_norm(f), 1e-11 * scale) << "damaged " << damaged << " C_hg " << C_hg;
            EXPECT_LT(max_off(th.sigma, th, 0.0), 1e-10 * p);
        }
}

TEST(CorrespondenceThermal, LinearClampedBodyIsUnderTheConstrainedThermalStress)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size(), theta_ref + heat);
    const double eps = alpha * heat;
    for (bool node_matrices : {true, false}) {
        C3 m({.material = mat, .node_matrices = node_matrices}, body, b);
        m.set_thermal_expansion({alpha, theta_ref, &theta});
        Field<3> f;
        internal_force(m, b, body.x, f);
        m.sync_node_matrices();
        EXPECT_LT(max_off(m.sigma, m, -3 * mat.K * eps), 1e-14 * mat.K);  // V7: -3 K alpha dtheta, to F's round-off
        const std::vector<double> W = m.energy_density(b, body.x);            // 9/2 K eps^2, constrained
        for (std::size_t i = 0; i < W.size(); ++i)
            if (!m.Kinv[i].isZero(0)) {  // round-off of F (W is quadratic in the strain)
                ASSERT_NEAR(W[i], 4.5 * mat.K * eps * eps, 1e-10 * mat.K * eps * eps) << i;
            }
    }
    // 2D plane stress: the in-plane constrained stress -E/(1 - nu) eps.
    const Body<2> plate = box<2>({{0, 0}}, {{12 * dx, 6 * dx}}, dx);
    const Bonds b2 = build_bonds(plate, 3 * dx);
    const std::vector<double> theta2(plate.size(), theta_ref + heat);
    Correspondence<2> m2({.material = mat, .plane = Plane::stress, .measure = dx}, plate, b2);
    m2.set_thermal_expansion({alpha, theta_ref, &theta2});
    Field<2> f2;
    internal_force(m2, b2, plate.x, f2);
    const double E = 9 * mat.K * mat.G / (3 * mat.K + mat.G), nu = (3 * mat.K - 2 * mat.G) / (2 * (3 * mat.K + mat.G));
    EXPECT_LT(max_off(m2.sigma, m2, -E / (1 - nu) * eps), 1e-14 * E);
}

TEST(CorrespondenceThermal, ReferenceTemperatureGivesTheIsothermalForcesBitForBit)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size(), theta_ref);
    Field<3> y = scaled(body, 1.001);
    for (std::size_t i = 0; i < y.size(); ++i) y.c[1][i] += 2e-4 * body.x.c[0][i] * body.x.c[0][i] / dx;
    C3 iso({.material = mat, .C_hg = 0.02}, body, b), th({.material = mat, .C_hg = 0.02}, body, b);
    th.set_thermal_expansion({alpha, theta_ref, &theta});
    Field<3> f_iso, f;
    internal_force(iso, b, y, f_iso);
    internal_force(th, b, y, f);
    for (int d = 0; d < 3; ++d) EXPECT_EQ(f.c[d], f_iso.c[d]);
}

TEST(CorrespondenceThermal, PlasticCorrespondenceTakesTheMechanicalStrain)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size(), theta_ref + heat);
    const laws::JohnsonCook law{.A = 5e8, .B = 1e8, .n = 0.5};  // 3 K eps = 0.24 GPa: elastic
    const double eps = alpha * heat;
    for (bool free : {false, true}) {
        PlasticCorrespondence m({.material = mat}, body, b, law);
        m.set_thermal_expansion({alpha, theta_ref, &theta});
        Field<3> f;
        internal_force(m, b, free ? scaled(body, 1 + eps) : body.x, f);
        const double s = free ? 0.0 : -3 * mat.K * eps;
        EXPECT_LT(max_off(m.model.sigma, m.model, s), 1e-10 * 3 * mat.K * eps) << "free " << free;  // round-off of F
        if (free) {  // P = J sigma F^-T = 0: far below 3 K eps / dx, the force density the thermal stress would leave
            EXPECT_LT(max_norm(f), 1e-3 * 3 * mat.K * eps / dx);
        }
    }
}

TEST(CorrespondenceThermal, RefusesWhatIsNotWritten)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size(), theta_ref + heat), short_theta(3, theta_ref);
    C3 svk({.material = mat, .law = C3::Law::saint_venant_kirchhoff}, body, b);
    EXPECT_THROW(svk.set_thermal_expansion({alpha, theta_ref, &theta}), std::invalid_argument);
    C3 lin({.material = mat}, body, b);
    EXPECT_THROW(lin.set_thermal_expansion({alpha, theta_ref, &short_theta}), std::invalid_argument);
    const Body<2> plate = box<2>({{0, 0}}, {{8 * dx, 6 * dx}}, dx);
    const Bonds b2 = build_bonds(plate, 3 * dx);
    const std::vector<double> theta2(plate.size(), theta_ref);
    Correspondence<2> strain({.material = mat, .plane = Plane::strain, .measure = dx}, plate, b2);
    EXPECT_THROW(strain.set_thermal_expansion({alpha, theta_ref, &theta2}), std::invalid_argument);
}
