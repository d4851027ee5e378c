// Thermal expansion of the ordinary models (models/thermal_expansion.hpp; spec/000a eq. 2.80 with
// erratum E9, verification case V7) for PMB, LPS, LPS with SCF and PALS:
// - a free body at y = (1 + eps) x with eps = alpha dtheta carries no force, also with broken bonds;
// - a body held at y = x has the dilatation -3 eps at every node and the energy density of a fully
//   constrained classical body, 9/2 K eps^2 (pressure 3 K eps, V7's hydrostatic -3 K alpha dtheta);
// - critical stretch compares the mechanical stretch;
// - the viscoelastic and plastic wrappers: free expansion carries no force, a clamped body the force of
//   the wrapped elastic model; the refusals.
// (Forces under a temperature field, the chunk path: test_thermal_expansion_forces.cpp.)
#include "pd/bond_loop.hpp"
#include "pd/core/lattice.hpp"
#include "pd/damage/critical_stretch.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/plastic_lps.hpp"
#include "pd/models/plastic_pals.hpp"
#include "pd/models/pmb.hpp"
#include "pd/models/viscoelastic_lps.hpp"

#include <gtest/gtest.h>

#include "thermal_expansion_fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <type_traits>
#include <vector>

using namespace pd;
using namespace pd_test::thermal_expansion_fixtures;

TEST(ThermalExpansion, FreeExpansionCarriesNoForce)
{
    const Body<3> body = bar();
    const std::vector<double> theta(body.size(), theta_ref + heat);
    const Field<3> y = scaled(body, 1 + alpha * heat);
    for (bool damaged : {false, true}) {
        Bonds b = build_bonds(body, 3 * dx);
        if (damaged) {
            b.enable_damage();
            for (std::size_t k = 0; k < b.size(); k += 7) b.break_pair(static_cast<std::int64_t>(k));
        }
        std::vector<double> scale;  // largest isothermal force at the same y
        for_each_model(b, body, nullptr, [&](const char*, auto& model) {
            if constexpr (requires { model.recompute(b); }) model.recompute(b);
            Field<3> f;
            internal_force(model, b, y, f);
            scale.push_back(max_norm(f));
        });
        int q = 0;
        for_each_model(b, body, &theta, [&](const char* name, auto& model) {
            if constexpr (requires { model.recompute(b); }) model.recompute(b);
            Field<3> f;
            internal_force(model, b, y, f);
            ASSERT_GT(scale[q], 0) << name;
            EXPECT_LE(max_norm(f), 1e-10 * scale[q++]) << name << (damaged ? ", damaged" : "");
        });
    }
}

TEST(ThermalExpansion, ClampedBodyIsUnderHydrostaticPressure)
{
    const Body<3> body = bar();
    Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size(), theta_ref + heat);
    const double eps = alpha * heat, W = 4.5 * mat.K * eps * eps;  // classical: K (tr eps_th)^2 / 2
    for_each_model(b, body, &theta, [&](const char* name, auto& model) {
        using M = std::decay_t<decltype(model)>;
        if constexpr (std::is_same_v<M, LPS> || std::is_same_v<M, PALS>) {
            model.point_pass(b, body.x);
            const std::vector<double> w = model.energy_density(b, body.x);
            for (std::size_t i = 0; i < body.size(); ++i) {  // every node, surfaces included
                if constexpr (std::is_same_v<M, LPS>) {
                    EXPECT_NEAR(model.theta[i], -3 * eps, 1e-12 * eps) << name << " node " << i;
                }
                EXPECT_NEAR(w[i], W, 1e-10 * W) << name << " node " << i;
            }
        }
    });
    // PMB, lattice calibration: exact at a node with a whole family; the bar is only 4-5 cells thick,
    // so the centre node of a 9-cell cube.
    const Body<3> cube = box<3>({{0, 0, 0}}, {{9 * dx, 9 * dx, 9 * dx}}, dx);
    Bonds bc = build_bonds(cube, 3 * dx);
    const std::vector<double> th(cube.size(), theta_ref + heat);
    PMB pmb({mat, 3, Plane::strain, 1, PMB::Params::Calibration::lattice, dx}, bc);
    pmb.set_thermal_expansion({alpha, theta_ref, &th});
    const int mid = 4 + 4 * 9 + 4 * 81;
    EXPECT_NEAR(pmb.energy_density(bc, cube.x)[mid], W, 1e-10 * W);
}

// The owner-node rule (spec/000a E9): at y = x under any temperature field, every LPS node has
// e_mech = -eps_i |xi| on all its bonds, hence theta_i = -3 eps_i and W_i = 9/2 K eps_i^2 whatever its
// neighbours' temperatures (a bond-mean rule would mix them in).
TEST(ThermalExpansion, ClampedLPSFollowsItsOwnNodesTemperature)
{
    const Body<3> body = bar();
    Bonds b = build_bonds(body, 3 * dx);
    std::mt19937 gen(13);
    std::uniform_real_distribution<double> T(-40, 40);
    std::vector<double> theta(body.size());
    for (auto& t : theta) t = theta_ref + heat + T(gen);
    for_each_model(b, body, &theta, [&](const char* name, auto& model) {
        if constexpr (std::is_same_v<std::decay_t<decltype(model)>, LPS>) {
            model.point_pass(b, body.x);
            const std::vector<double> w = model.energy_density(b, body.x);
            for (std::size_t i = 0; i < body.size(); ++i) {
                const double eps = alpha * (theta[i] - theta_ref), W = 4.5 * mat.K * eps * eps;
                EXPECT_NEAR(model.theta[i], -3 * eps, 1e-12 * std::abs(eps)) << name << " node " << i;
                EXPECT_NEAR(w[i], W, 1e-10 * W) << name << " node " << i;
            }
        }
    });
}

// Critical stretch with the model's thermal expansion: a body heated free to eps = 2 s0 breaks no
// bond (mechanical stretch 0) and every bond without it; the same body pulled mechanically to
// (1 + eps + 2 s0) x breaks every bond.
TEST(ThermalExpansion, CriticalStretchComparesTheMechanicalStretch)
{
    const Body<3> body = bar();
    const std::vector<double> theta(body.size(), theta_ref + heat);
    const double eps = alpha * heat, s0 = eps / 2;
    for (double pull : {0.0, 2 * s0})
        for (bool thermal : {true, false}) {
            Bonds b = build_bonds(body, 3 * dx);
            b.enable_damage();
            CriticalStretch rule = CriticalStretch::uniform(s0);
            if (thermal) rule.thermal = {alpha, theta_ref, &theta};
            const long broken = rule.apply(b, scaled(body, 1 + eps + pull));
            EXPECT_EQ(broken, thermal && pull == 0 ? 0 : static_cast<long>(b.size())) << "pull " << pull << (thermal ? ", thermal" : "");
        }
}

TEST(ThermalExpansion, RefusesATemperatureFieldOfAnotherBody)
{
    const Body<3> body = bar();
    Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size() - 1, theta_ref);
    PMB pmb({mat, 3}, b);
    LPS lps({mat, 3}, b);
    EXPECT_THROW(pmb.set_thermal_expansion({alpha, theta_ref, &theta}), std::invalid_argument);
    EXPECT_THROW(lps.set_thermal_expansion({alpha, theta_ref, &theta}), std::invalid_argument);
    EXPECT_THROW(lps.set_thermal_expansion({NAN, theta_ref, nullptr}), std::invalid_argument);
}

// The wrappers with a deviatoric extension of their own (viscoelastic LPS, plastic LPS and PALS) take
// the mechanical one: a heated body free to expand carries no force, and a clamped heated body carries
// exactly the force of the wrapped elastic model (the isotropic thermal strain neither loads the
// viscous branch nor reaches the yield surface, although the pressure 3 K eps = 0.24 GPa is above the
// yield stress 0.1 GPa: J2 does not see it). Errors: round-off of the family sums.
TEST(ThermalExpansion, WrappersTakeTheMechanicalDeviatoricExtension)
{
    const Body<3> body = bar();
    Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size(), theta_ref + heat);
    const ThermalExpansion t{alpha, theta_ref, &theta};
    const laws::JohnsonCook soft{.A = 1e8, .B = 0, .n = 1};
    const double dt = 1e-7;
    LPS lps({mat, 3}, b);
    PALS pals({.material = mat}, body, b);
    lps.set_thermal_expansion(t), pals.set_thermal_expansion(t);
    ViscoelasticLPS visco({{mat, 3}, 2.0, 1e-6}, b);
    PlasticLPS plps({.material = mat, .dim = 3}, b, soft);
    PlasticPALS ppals({.material = mat}, body, b, soft);
    visco.lps.set_thermal_expansion(t), plps.lps.set_thermal_expansion(t), ppals.pals.set_thermal_expansion(t);
    const Field<3> free = scaled(body, 1 + alpha * heat);
    auto check = [&](const char* name, auto& wrapper, auto& base) {
        Field<3> fw, fb, iso;
        internal_force(base, b, body.x, fb);
        const double scale = max_norm(fb);  // the clamped body's surface forces
        ASSERT_GT(scale, 0) << name;
        internal_force(wrapper, b, body.x, dt, fw);
        double diff = 0;
        for (std::size_t i = 0; i < body.size(); ++i) diff = std::max(diff, norm(fw[i] - fb[i]));
        EXPECT_LE(diff, 1e-10 * scale) << name << ", clamped";
        internal_force(wrapper, b, free, dt, fw);
        EXPECT_LE(max_norm(fw), 1e-10 * scale) << name << ", free";
    };
    check("viscoelastic LPS", visco, lps);
    check("plastic LPS", plps, lps);
    check("plastic PALS", ppals, pals);
}

// What is not written says so instead of ignoring part of it: 2D plane strain.
TEST(ThermalExpansion, PlaneStrainIsRefused)
{
    const Body<2> plate = box<2>({{0, 0}}, {{6 * dx, 6 * dx}}, dx, dx);
    Bonds b2 = build_bonds(plate, 3 * dx);
    const std::vector<double> theta2(plate.size(), theta_ref + heat);
    LPS strain({mat, 2, Plane::strain}, b2), stress({mat, 2, Plane::stress}, b2);
    EXPECT_THROW(strain.set_thermal_expansion({alpha, theta_ref, &theta2}), std::invalid_argument);
    EXPECT_NO_THROW(stress.set_thermal_expansion({alpha, theta_ref, &theta2}));
}
