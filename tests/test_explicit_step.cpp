// The explicit step (time/explicit_step.hpp): the highest natural frequency by power iteration, the step
// chosen from it, and the Gershgorin step of a stiffness bound, against closed forms and an independent
// dense eigen-decomposition:
//   two free unit masses on one spring k: omega_max^2 = 2 k / m (closed form);
//   the Gershgorin rows of that pair (|k| + |-k|) give the same step; an inelastic model's bound is its
//   elastic model's, times 1 + gamma_b for a standard linear solid (its instantaneous moduli);
//   small 3D bodies: the largest eigenvalue of M^-1/2 K_s M^-1/2, K assembled column by column by
//   finite differences (common/analysis/stiffness_matrix.hpp) and solved by Eigen -- another method for
//   the same number, which the power iteration must reach from below within its convergence (1 %).
#include "pd/models/dissipative_registry.hpp"
#include "pd/models/stiffness_bound.hpp"
#include "pd/time/explicit_step.hpp"
#include "problems/common/analysis/stiffness_matrix.hpp"

#include "damage_fixtures.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>

using namespace pd;

namespace {
constexpr double dx = 1e-3, rho = 7800;
const Elastic steel = Elastic::from_E_nu(200e9, 0.3);

// omega_max by the dense eigen-decomposition of the assembled stiffness [rad/s].
template <class Model>
double dense_omega_max(Model& model, const Body<3>& body, const Bonds& bonds)
{
    const Eigen::MatrixXd K = fd_stiffness(model, body, bonds, 1e-6 * dx);
    Eigen::VectorXd w(K.rows());
    for (Eigen::Index r = 0; r < K.rows(); ++r) w(r) = 1 / std::sqrt(rho * body.volume[r / 3]);
    const Eigen::MatrixXd S = w.asDiagonal() * (0.5 * (K + K.transpose())) * w.asDiagonal();
    return std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff());
}

}  // namespace

// Two nodes 1 m apart, PMB 1D, E = 1/2, A = V = 1, rho = 1: k = 1 (test_gershgorin_step.cpp), so
// omega_max = sqrt(2) rad/s.
TEST(HighestMode, TwoFreeMassesClosedForm)
{
    const Body<1> body = box<1>({{0}}, {{2.0}}, 1.0, 1.0);
    const Bonds bonds = build_bonds(body, 1.0);
    PMB pmb{{Elastic::from_E_nu(0.5, 0.25), 1, Plane::stress, 1.0}, bonds};
    EXPECT_NEAR(highest_frequency(pmb, bonds, body, 1.0), std::sqrt(2.0), 1e-6);  // the probe's linearisation: ~1e-7
}

// Undamaged and damaged bodies, every elastic model: the power iteration reaches the dense value from
// below within 1 % (measured: within 0.2 %, LPS on the intact cube).
TEST(HighestMode, MatchesDenseEigenvalues)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{5 * dx, 5 * dx, 5 * dx}}, dx);
    for (int broken : {0, 90}) {  // percent of the pairs
        for (const char* name : {"pmb", "lps", "pals", "correspondence"}) {
            Bonds bonds = build_bonds(body, 3.05 * dx);
            if (broken > 0) pd_test::mark(bonds, pd_test::random_pairs(-1, broken));
            with_model(ModelChoice{.name = name, .material = steel, .C_hg = 0.02}, body, bonds, [&](auto& model) {
                if constexpr (BondDependentModel<std::decay_t<decltype(model)>>) model.recompute(bonds);
                const double power = highest_frequency(model, bonds, body, rho), dense = dense_omega_max(model, body, bonds);
                if (std::string(name) != "pals" || broken == 0) {  // PALS at 90 %: unstable modes, see stability_atlas.md
                    // from below: a Rayleigh quotient; 1e-6 for the linearisation of the probe (1e-7 delta) and of the FD step
                    EXPECT_LT(power, dense * (1 + 1e-6)) << name << " " << broken;
                    EXPECT_GT(power, 0.99 * dense) << name << " " << broken;
                }
                return 0;
            });
        }
    }
}

// The step: 0.5 dt_SA on an undamaged body (the mode step lies above dt_SA), the mode step where
// 90 % of the pairs are broken under correspondence (K^-1 of a depleted family: stiffer).
TEST(HighestMode, ExplicitStepTakesTheModeWhereSillingAskariCannotSeeIt)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{5 * dx, 5 * dx, 5 * dx}}, dx);
    for (int broken : {0, 90}) {  // percent of the pairs
        Bonds bonds = build_bonds(body, 3.05 * dx);
        if (broken > 0) pd_test::mark(bonds, pd_test::random_pairs(-1, broken));
        const double c = PMB::micromodulus({.material = steel, .dim = 3}, bonds.influence, bonds.delta);
        Correspondence<3> model({.material = steel, .C_hg = 0.02}, body, bonds);
        const ExplicitStep s = explicit_step(model, bonds, body, rho, c);
        EXPECT_EQ(s.silling_askari.dt, critical_step_silling_askari(bonds, rho, c).dt);
        EXPECT_EQ(s.mode_limits, broken > 0) << broken;
        EXPECT_EQ(s.dt, 0.5 * std::min(s.silling_askari.dt, s.mode_step));
    }
}

// Models without a positional force go through the elastic model with their tangent: Flanagan-Taylor
// correspondence through its linear twin (the same number), a standard linear solid with omega^2
// times 1 + gamma_b.
TEST(HighestMode, InelasticAndRateFormModelsUseTheirElasticTangent)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{4 * dx, 4 * dx, 4 * dx}}, dx);
    const Bonds bonds = build_bonds(body, 3.05 * dx);
    Correspondence<3> linear({.material = steel, .C_hg = 0.02}, body, bonds);
    Correspondence<3> ft({.material = steel, .law = Correspondence<3>::Law::flanagan_taylor, .C_hg = 0.02}, body, bonds);
    EXPECT_EQ(highest_frequency(ft, bonds, body, rho), highest_frequency(linear, bonds, body, rho));
    LPS lps({.material = steel, .dim = 3}, bonds);
    const double w = highest_frequency(lps, bonds, body, rho);
    with_dissipative_model<ViscoelasticLPS>({.name = "lps", .material = steel}, {.kind = Dissipation::Kind::viscoelastic, .gamma_b = 3},
                                           body, bonds, [&](auto& m) {
                                               EXPECT_NEAR(highest_frequency(m, bonds, body, rho), 2 * w, 1e-9 * w);
                                               return 0;
                                           });
}

// Two nodes 1 m apart, PMB 1D, delta = 1 m, A = V = 1, E = 1/2, rho = 1: the bond's force density
// per displacement is k = 1 (test_stability_sweep.cpp: omega = 1 with one node fixed), so the free
// pair has omega_max^2 = 2 k / rho = 2 and Verlet's limit sqrt(2) s; the Gershgorin row is 2 k.
TEST(GershgorinStep, TwoFreeMassesGiveVerletLimit)
{
    const Body<1> body = box<1>({{0}}, {{2.0}}, 1.0, 1.0);
    const Bonds bonds = build_bonds(body, 1.0);
    const PMB pmb{{Elastic::from_E_nu(0.5, 0.25), 1, Plane::stress, 1.0}, bonds};
    const CriticalStep s = critical_step_gershgorin(stiffness_bound(pmb, bonds, body.x), 1.0);
    EXPECT_NEAR(s.dt, std::sqrt(2.0), 1e-12);
    EXPECT_GE(s.node, 0);
}

TEST(GershgorinStep, InelasticModelsTakeTheirElasticBound)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{4 * dx, 4 * dx, 4 * dx}}, dx);
    const Bonds bonds = build_bonds(body, 2.015 * dx);
    const LPS lps({.material = steel, .dim = 3}, bonds);
    const Field<3> G = stiffness_bound(lps, bonds, body.x);
    const ModelChoice c{.name = "lps", .material = steel};
    with_dissipative_model<ViscoelasticLPS, PlasticLPS>(c, {.kind = Dissipation::Kind::viscoelastic, .gamma_b = 1.5}, body, bonds, [&](auto& m) {
        const Field<3> Gv = stiffness_bound_of(m, bonds, body.x);
        EXPECT_NEAR(Gv.c[1][7] / G.c[1][7], 2.5, 1e-12);
        return 0;
    });
    with_dissipative_model<ViscoelasticLPS, PlasticLPS>(c, {.kind = Dissipation::Kind::plastic, .law = {.A = 1e9}}, body, bonds, [&](auto& m) {
        EXPECT_EQ(stiffness_bound_of(m, bonds, body.x).c[2][11], G.c[2][11]);
        return 0;
    });
}
