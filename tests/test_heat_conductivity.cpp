// Temperature-dependent conductivity k(theta) (heat/conductivity.hpp, properties.hpp; tracker issue 4):
// property values, the constant-k path, heat conservation of the symmetric bond rule, Picard failure,
// the critical step with k_max, and the three integrators on one transient. Steady bar, interior flux
// divergence and the Kirchhoff references: test_heat_conductivity_steady.cpp.
#include "pd/heat/agwai.hpp"
#include "pd/heat/conductivity.hpp"
#include "pd/heat/correspondence_heat.hpp"
#include "pd/time/heat_cvode.hpp"

#include <gtest/gtest.h>

#include "heat_conductivity_fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <type_traits>
#include <vector>

using namespace pd_test::heat_conductivity_fixtures;

TEST(Conductivity, PropertyValuesAndBounds)
{
    // EN 1993-1-2 eq. (3.13), by hand: 54 - 0.0333 * 20 = 53.334, 54 - 0.0333 * 400 = 40.68, 27.3 from 800 C.
    const auto k = pd::en1993_carbon_steel_conductivity();
    EXPECT_NEAR(k(20), 53.334, 1e-12);
    EXPECT_NEAR(k(400), 40.68, 1e-12);
    EXPECT_NEAR(k(std::nextafter(800.0, 0.0)), 27.36, 1e-9);
    EXPECT_EQ(k(800), 27.3);
    EXPECT_EQ(k(1500), 27.3);                 // clamped above 1200 C
    EXPECT_NEAR(k(0), 53.334, 1e-12);          // clamped below 20 C
    EXPECT_FALSE(k.is_constant());
    EXPECT_TRUE(pd::Property::constant(3).is_constant());
    // max_over: decreasing law -> value at the low end; table -> its interior peak.
    EXPECT_NEAR(k.max_over(100, 1000), 54 - 3.33, 1e-12);
    const auto t = pd::Property::table({0, 10, 30}, {1, 2, 0});
    EXPECT_EQ(t.max_over(0, 30), 2.0);
    EXPECT_EQ(t.max_over(15, 30), 1.5);       // t(15) = 2 - 2 * 5/20, decreasing on [15, 30]
    EXPECT_EQ(pd::Property::constant(7).max_over(-1, 1), 7.0);
}

TEST(Conductivity, ConstantKTakesThePlainModelBitForBit)
{
    Bar bar(20);
    std::vector<double> theta(bar.body.size()), Q_direct, Q_visit;
    for (std::size_t i = 0; i < theta.size(); ++i) theta[i] = 20 + 1e4 * bar.body.x.c[0][i] * bar.body.x.c[0][i];
    pd::Agwai direct({50, Bar::A}, bar.body, bar.bonds);
    pd::heat_flow(direct, bar.bonds, theta, Q_direct);
    const bool plain = pd::with_conductivity<pd::Agwai>({0, Bar::A}, pd::Property::constant(50), bar.body, bar.bonds, [&](auto& model) {
        pd::heat_flow(model, bar.bonds, theta, Q_visit);
        return std::is_same_v<std::decay_t<decltype(model)>, pd::Agwai>;
    });
    EXPECT_TRUE(plain);
    for (std::size_t i = 0; i < theta.size(); ++i) EXPECT_EQ(Q_visit[i], Q_direct[i]) << i;  // same code path: identical
    // The wrapper itself with a constant property agrees to round-off (k enters as 50 * kappa_1(1)
    // instead of kappa_1(50): a few ulps per bond, 1e-13 of the largest |Q|).
    pd::ConductivityOfTheta<pd::Agwai> wrapped({0, Bar::A}, pd::Property::table({-1e4, 1e4}, {50, 50}), bar.body, bar.bonds);
    std::vector<double> Q_wrapped;
    pd::heat_flow(wrapped, bar.bonds, theta, Q_wrapped);
    double qmax = 0;
    for (double q : Q_direct) qmax = std::max(qmax, std::abs(q));
    for (std::size_t i = 0; i < theta.size(); ++i) EXPECT_NEAR(Q_wrapped[i], Q_direct[i], 1e-13 * qmax) << i;
}

// Insulated body (no held node, no source): the total heat sum_i V_i rho c theta_i stays constant
// to round-off under explicit Euler, for Agwai and correspondence heat with k(theta).
template <class Model>
void check_conservation(const pd::Body<2>& body, const pd::Bonds& bonds, Model& model)
{
    const double rho_c = 4e6;  // [J/(m^3 K)]
    pd::Conduction<Model> heat(model, bonds, std::vector<double>(body.size(), rho_c), {});
    std::vector<double> theta(body.size());
    for (std::size_t i = 0; i < theta.size(); ++i)
        theta[i] = 20 + 7e5 * body.x.c[0][i] + 2e5 * body.x.c[1][i];  // ramp over the plate [C]
    auto total = [&] {
        double E = 0;
        for (std::size_t i = 0; i < theta.size(); ++i) E += body.volume[i] * rho_c * theta[i];
        return E;
    };
    const double E0 = total();
    const double dt = 0.5 * pd::thermal_critical_step_k(model, bonds, heat, theta, 20, 720);
    for (int n = 0; n < 200; ++n) heat.explicit_euler(theta, dt);
    double spread = 0;
    for (double t : theta) spread = std::max(spread, std::abs(t - theta[0]));
    EXPECT_GT(spread, 1.0);  // still a non-uniform field: the test is not trivially satisfied
    // 200 steps of ~100 nodes, each update a few roundings of theta ~ 700: 1e-13 relative.
    EXPECT_NEAR(total(), E0, 1e-13 * E0);
}

TEST(Conductivity, SymmetricBondRuleConservesHeat)
{
    const double dx = 1e-3;  // 10 x 8 plate [m]
    const auto body = pd::box<2>(pd::Vec<2>{0, 0}, pd::Vec<2>{10 * dx, 8 * dx}, dx, 1e-3);
    const auto bonds = pd::build_bonds(body, 3.05 * dx);
    const auto k = pd::en1993_carbon_steel_conductivity();
    pd::ConductivityOfTheta<pd::Agwai> agwai({0, 1e-3}, k, body, bonds);
    check_conservation(body, bonds, agwai);
    pd::ConductivityOfTheta<pd::CorrespondenceHeat<2>> corr({0, 1.0, 1e-3}, k, body, bonds);
    check_conservation(body, bonds, corr);
}

TEST(Conductivity, PicardFailureIsReported)
{
    Bar bar(20);
    pd::ConductivityOfTheta<pd::Agwai> model({0, Bar::A}, linear_k(), bar.body, bar.bonds);
    pd::HeatLoads loads;
    for (std::size_t i = 0; i < bar.body.size(); ++i)
        if (bar.outside(i)) loads.fixed.push_back(int(i)), loads.fixed_value.push_back(bar.body.x.c[0][i] < 0 ? 100 : 900);
    pd::Conduction<pd::ConductivityOfTheta<pd::Agwai>> heat(model, bar.bonds, std::vector<double>(bar.body.size(), Bar::rho_c), loads);
    heat.picard_max_iter = 2;  // k varies by 40 %: two iterations cannot reach 1e-10
    std::vector<double> theta(bar.body.size(), 20.0);
    EXPECT_THROW(heat.implicit_euler(theta, 1000), std::runtime_error);
    EXPECT_THROW(heat.steady_state(theta), std::runtime_error);
}

TEST(Conductivity, CriticalStepUsesTheLargestConductivity)
{
    // k falls with T: on [100, 900] the largest k is k(100) = 47.5, so the step is the Gershgorin step
    // of the plain model at k = 47.5, by hand: an interior node of the 1D Agwai bar (no held node, no
    // correction, full volumes A dx) has g = sum_j kappa_1 A dx/|xi| = 2k/(A delta^2) A 2 (1 + 1/2 + 1/3)
    // = 22 k / (3 delta^2) for m = 3, so dt = rho c / g = 3 rho c delta^2 / (22 k). 1e-12 for the
    // roundings of the bond sums and of the scaling.
    Bar bar(40);
    pd::ConductivityOfTheta<pd::Agwai> model({0, Bar::A}, linear_k(), bar.body, bar.bonds);
    const std::vector<double> rc(bar.body.size(), Bar::rho_c), theta(bar.body.size(), 500.0);
    pd::Conduction<pd::ConductivityOfTheta<pd::Agwai>> heat(model, bar.bonds, rc, {});
    const double dt = pd::thermal_critical_step_k(model, bar.bonds, heat, theta, 100, 900);
    const double delta = Bar::m * bar.dx, k_max = k0 * (1 + beta * (100 - Tk));  // [m], 47.5 W/(m K)
    EXPECT_NEAR(dt, 3 * Bar::rho_c * delta * delta / (22 * k_max), 1e-12 * dt);
}

// Bar at 20 C, ends held at 900 C; the profile at t = 60 s. Reference: CVODE at rtol 1e-10.
template <class Model>
void integrators_agree(const typename Model::Params& params)
{
    Bar bar(40);
    Model model(params, pd::en1993_carbon_steel_conductivity(), bar.body, bar.bonds);
    pd::HeatLoads loads;
    for (std::size_t i = 0; i < bar.body.size(); ++i)
        if (bar.outside(i)) loads.fixed.push_back(int(i)), loads.fixed_value.push_back(900);
    pd::Conduction<Model> heat(model, bar.bonds, std::vector<double>(bar.body.size(), Bar::rho_c), loads);
    const std::vector<double> theta0(bar.body.size(), 20.0);
    const double t_end = 60;
    pd::CvodeOptions opt;
    opt.rtol = 1e-10, opt.atol = 1e-8;
    const std::vector<double> ref = pd::HeatCvode<Model>(heat, model, bar.bonds, theta0, 0, opt).advance(t_end);
    auto error = [&](bool implicit, int steps) {
        std::vector<double> theta = theta0;
        heat.apply_fixed(theta);
        for (int n = 0; n < steps; ++n) implicit ? heat.implicit_euler(theta, t_end / steps) : heat.explicit_euler(theta, t_end / steps);
        double e = 0;
        for (std::size_t i = 0; i < theta.size(); ++i) e = std::max(e, std::abs(theta[i] - ref[i]));
        return e;
    };
    const double dt_crit = pd::thermal_critical_step_k(model, bar.bonds, heat, theta0, 20, 900);
    const int n_exp = int(std::ceil(t_end / (0.5 * dt_crit)));
    const double e_exp = error(false, n_exp), e_exp2 = error(false, 2 * n_exp);
    const double e_imp = error(true, 60), e_imp2 = error(true, 120);
    std::printf("transient k(T): explicit %.3e / %.3e K, implicit %.3e / %.3e K (steps %d/%d, 60/120)\n", e_exp, e_exp2,
                e_imp, e_imp2, n_exp, 2 * n_exp);
    // Both Euler schemes are first order: halving dt halves the error (ratio 2 +- 0.25, the O(dt^2) rest).
    EXPECT_NEAR(e_exp / e_exp2, 2.0, 0.25);
    EXPECT_NEAR(e_imp / e_imp2, 2.0, 0.25);
    // A loose CVODE (rtol 1e-6) against the tight one: its error control keeps it within 1e-3 K of 900 K spans.
    opt.rtol = 1e-6, opt.atol = 1e-4;
    const std::vector<double> loose = pd::HeatCvode<Model>(heat, model, bar.bonds, theta0, 0, opt).advance(t_end);
    for (std::size_t i = 0; i < loose.size(); ++i) EXPECT_NEAR(loose[i], ref[i], 1e-3) << i;
}

TEST(Conductivity, ImplicitExplicitAndCvodeAgreeOnATransient)
{
    integrators_agree<AgwaiK>(agwai_params);
    integrators_agree<CorrK>(corr_params);
}
