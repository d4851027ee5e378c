// Temperature-dependent properties (heat/properties.hpp), their use by the three heat integrators,
// and a stiff scene in which explicit Euler collapses while implicit Euler and CVODE hold
// (spec/000a sec. 3.9, V2, V4; tracker issue 4).
#include "pd/heat/agwai.hpp"
#include "pd/heat/conduction.hpp"
#include "pd/heat/properties.hpp"
#include "pd/time/heat_time_to_reach.hpp"
#include "pd/core/lattice.hpp"
#include "reference/enthalpy.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace {

// 2 x 2 x 2 nodes, dx = 1 m, delta = 1.5 m, Agwai conduction: the tiny adiabatic mesh of spec V2.
struct TinyMesh {
    pd::Body<3> body = pd::box<3>(pd::Vec<3>{0, 0, 0}, pd::Vec<3>{2, 2, 2}, 1.0);
    pd::Bonds bonds = pd::build_bonds(body, 1.5);
    pd::Agwai model{{45.0, 1.0}, body, bonds};
};

// Conduction with rho = 1 kg/m^3, uniform source s = 1 W/m^3, c(theta) of carbon steel.
pd::Conduction<pd::Agwai> heating(TinyMesh& m)
{
    pd::HeatLoads loads;
    loads.source.assign(m.body.size(), 1.0);
    pd::Conduction<pd::Agwai> heat(m.model, m.bonds, std::vector<double>(m.body.size(), 1.0), loads);
    heat.rho_c_of = [c = pd::en1993_carbon_steel_specific_heat()](std::size_t, double theta) { return 1.0 * c(theta); };
    return heat;
}

}  // namespace

TEST(Property, ConstantPiecewiseAndTable)
{
    EXPECT_EQ(pd::Property::constant(3.5)(-1e6), 3.5);
    const auto p = pd::Property::piecewise({{0, 1, [](double t) { return t; }}, {1, 2, [](double t) { return 10 * t; }}});
    EXPECT_EQ(p(0.5), 0.5);
    EXPECT_EQ(p(1.0), 10.0);   // a boundary belongs to the branch on its right
    EXPECT_EQ(p(2.0), 20.0);   // the upper end belongs to the last branch
    EXPECT_EQ(p(-3.0), 0.0);   // clamped to p(0)
    EXPECT_EQ(p(5.0), 20.0);   // clamped to p(2)
    const auto t = pd::Property::table({0, 10, 30}, {1, 2, 0});
    EXPECT_DOUBLE_EQ(t(5), 1.5);   // halfway between (0, 1) and (10, 2)
    EXPECT_DOUBLE_EQ(t(25), 0.5);  // three quarters from (10, 2) to (30, 0)
    EXPECT_EQ(t(30), 0.0);
    EXPECT_EQ(t(-1), 1.0);
    const auto strict = pd::Property::table({0, 10}, {1, 2}, pd::OutOfRange::error);
    EXPECT_THROW(strict(10.5), std::out_of_range);
    EXPECT_THROW(pd::Property::table({0, 0}, {1, 2}), std::invalid_argument);
    EXPECT_THROW(pd::Property::piecewise({{0, 1, [](double) { return 1.0; }}, {2, 3, [](double) { return 1.0; }}}),
                 std::invalid_argument);  // gap between the intervals
}

TEST(Property, CarbonSteelSpecificHeatSpecValues)
{
    // Spec/000a V2, J/(kg K), printed to 0.01: c(20) = 439.80, c(600-) = 759.92, c(600+) = 760.22,
    // c(735) = 5000 from both sides, c(740) = 2525.0, c(900-) = 650.44, c >= 900 = 650.
    const auto c = pd::en1993_carbon_steel_specific_heat();
    EXPECT_NEAR(c(20), 439.80, 0.005);
    EXPECT_NEAR(c(std::nextafter(600.0, 0.0)), 759.92, 0.005);
    EXPECT_NEAR(c(600), 760.22, 0.005);
    EXPECT_NEAR(c(std::nextafter(735.0, 0.0)), 5000.0, 1e-6);
    EXPECT_NEAR(c(735), 5000.0, 1e-9);
    EXPECT_NEAR(c(740), 2525.0, 1e-9);
    EXPECT_NEAR(c(std::nextafter(900.0, 0.0)), 650.44, 0.005);
    EXPECT_EQ(c(1200), 650.0);
    EXPECT_EQ(c(1300), 650.0);                 // clamped above 1200 C
    EXPECT_NEAR(c(0), 439.80, 0.005);          // clamped below 20 C
    EXPECT_THROW(pd::en1993_carbon_steel_specific_heat(pd::OutOfRange::error)(1201), std::out_of_range);
}

TEST(Property, EulerStepsUseTheSpecificHeatAtTheCurrentTemperature)
{
    // One step of dt = 100 s from 20 C: theta = 20 + dt s / (rho c(20)) = 20 + 100/439.80176 (hand
    // value of c(20)); implicit Euler lags rho c at theta^n, so it takes the same step here (Q = 0).
    const double expected = 20 + 100 / 439.80176;
    for (bool implicit : {false, true}) {
        TinyMesh m;
        auto heat = heating(m);
        std::vector<double> theta(m.body.size(), 20.0);
        implicit ? heat.implicit_euler(theta, 100) : heat.explicit_euler(theta, 100);
        for (double t : theta) EXPECT_NEAR(t, expected, 1e-12 * expected) << (implicit ? "implicit" : "explicit");
    }
}

TEST(Property, CvodeReachesTheExactEnthalpyTime)
{
    // rho = 1, s = 1: the time to 1200 C is q(1200) = 827063.84 s (reference/enthalpy). CVODE at
    // rtol 1e-10: its error control keeps the time within 1e-6 relative (the crossing bisection is 1e-12).
    TinyMesh m;
    auto heat = heating(m);
    pd::CvodeOptions opt;
    opt.rtol = 1e-10, opt.atol = 1e-8;
    const pd::Probe first = [](const std::vector<double>& T) { return T[0]; };
    const auto r = pd::time_to_reach(heat, m.model, m.bonds, std::vector<double>(m.body.size(), 20.0),
                                     pd::HeatIntegrator::cvode, 0, opt, 2e6, first, 1200.0);
    ASSERT_TRUE(r.reached);
    const double exact = pd::ref::adiabatic_heating_time(1, 1, 20, 1200);
    EXPECT_NEAR(r.t, exact, 1e-6 * exact);
    // Target on the jump of c at 600 C: CVODE's steps shrink there below the spacing of doubles at
    // t ~ 3e5 s, and the crossing bisection must still end (it looped forever before).
    const auto r600 = pd::time_to_reach(heat, m.model, m.bonds, std::vector<double>(m.body.size(), 20.0),
                                        pd::HeatIntegrator::cvode, 0, opt, 2e6, first, 600.0);
    ASSERT_TRUE(r600.reached);
    EXPECT_NEAR(r600.t, pd::ref::adiabatic_heating_time(1, 1, 20, 600), 1e-6 * r600.t);
}

// Stiff scene (tracker issue 4): the 1D Agwai bar of spec T7 with k x 1000 and N = 400 cells, ends
// held at 100 C from 0 C. The true critical step of explicit Euler is 2 rho c / |lambda_max| of the
// free block of the heat operator (symmetric here: uniform volumes, no correction).
namespace {
struct StiffBar {
    static constexpr double l = 0.1, A = 1e-4, rho_c = 7800 * 502.08, k = 50e3;  // [m, m^2, J/(m^3 K), W/(m K)]
    static constexpr int N = 400, m = 3;
    double dx = l / N;
    pd::Body<1> body = pd::box<1>(pd::Vec<1>{-m * dx}, pd::Vec<1>{l + m * dx}, dx, A);
    pd::Bonds bonds = make_bonds();
    pd::Agwai model{{k, A}, body, bonds};
    pd::Bonds make_bonds() const
    {
        pd::BondOptions bo;
        bo.partial_volume = pd::PartialVolume::pa_pdlammps;
        return pd::build_bonds(body, m * dx, bo);
    }
    pd::Conduction<pd::Agwai> conduction()
    {
        pd::HeatLoads loads;
        for (std::size_t i = 0; i < body.size(); ++i)
            if (body.x.c[0][i] < 0 || body.x.c[0][i] > l) loads.fixed.push_back(int(i)), loads.fixed_value.push_back(100);
        return pd::Conduction<pd::Agwai>(model, bonds, std::vector<double>(body.size(), rho_c), loads);
    }
    double true_critical_step(const pd::Conduction<pd::Agwai>& heat) const
    {
        const Eigen::MatrixXd A_full = Eigen::MatrixXd(pd::heat_operator(model, bonds));
        std::vector<int> free;
        for (std::size_t i = 0; i < body.size(); ++i)
            if (!heat.held(i)) free.push_back(int(i));
        Eigen::MatrixXd F(free.size(), free.size());
        for (std::size_t a = 0; a < free.size(); ++a)
            for (std::size_t b = 0; b < free.size(); ++b) F(a, b) = A_full(free[a], free[b]);
        EXPECT_LT((F - F.transpose()).norm(), 1e-12 * F.norm());
        const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(F).eigenvalues();
        return 2 * rho_c / lambda.cwiseAbs().maxCoeff();
    }
};
}  // namespace

TEST(StiffScene, ExplicitEulerCollapsesAboveTheCriticalStep)
{
    StiffBar bar;
    auto heat = bar.conduction();
    const double dt_true = bar.true_critical_step(heat);
    const std::vector<double> theta0(bar.body.size(), 0.0);
    std::printf("stiff bar: true critical step %.4g s, Gershgorin bound %.4g s\n", dt_true,
                pd::thermal_critical_step(bar.model, bar.bonds, heat, theta0));
    // Gershgorin bound (thermal_critical_step) is a lower bound of the true critical step.
    EXPECT_LE(pd::thermal_critical_step(bar.model, bar.bonds, heat, theta0), dt_true * (1 + 1e-12));
    // A probe target that is never met: the run goes to t_max unless it becomes non-finite.
    const pd::Probe never = [](const std::vector<double>&) { return 0.0; };
    const pd::CvodeOptions unused;
    EXPECT_THROW(pd::time_to_reach(heat, bar.model, bar.bonds, theta0, pd::HeatIntegrator::explicit_euler,
                                   1.1 * dt_true, unused, 10000 * dt_true, never, 1.0),
                 pd::Unstable);  // the top mode grows by |1 - 2.2| = 1.2 per step: overflow in ~4000 steps
    std::vector<double> theta = theta0;
    heat.apply_fixed(theta);
    for (int n = 0; n < 10000; ++n) heat.explicit_euler(theta, 0.9 * dt_true);  // every mode damps (|1 - 1.8| < 1)
    for (double t : theta) {
        EXPECT_GE(t, -1e-9);  // maximum principle, to round-off
        EXPECT_LE(t, 100 + 1e-9);
    }
}

TEST(StiffScene, ImplicitEulerAndCvodeHoldAtThousandTimesTheCriticalStep)
{
    StiffBar bar;
    auto heat = bar.conduction();
    const double dt_true = bar.true_critical_step(heat);
    const std::vector<double> theta0(bar.body.size(), 0.0);
    const int a = StiffBar::m + (StiffBar::N - 1) / 2, b = StiffBar::m + StiffBar::N / 2;
    const pd::Probe centre = [a, b](const std::vector<double>& T) { return 0.5 * (T[a] + T[b]); };
    pd::CvodeOptions opt;
    opt.rtol = 1e-8, opt.atol = 1e-6;
    const auto cv = pd::time_to_reach(heat, bar.model, bar.bonds, theta0, pd::HeatIntegrator::cvode, 0, opt, 1.0, centre, 50.0);
    ASSERT_TRUE(cv.reached);
    // CVODE is not bound by the stability limit: at rtol 1e-8 it takes under a tenth of the steps
    // explicit Euler needs at dt_true.
    EXPECT_LT(double(cv.steps), 0.1 * cv.t / dt_true);
    std::printf("stiff bar: dt_true %.4g s, t50 CVODE %.9g s in %ld steps (explicit Euler: %.0f steps at dt_true)\n",
                dt_true, cv.t, cv.steps, cv.t / dt_true);
    // Implicit Euler, first order: relative error about 0.8 dt / t50 (0.059 at dt/t50 = 0.13 in the
    // agwai_bar work-precision table); bounds 0.1 at 1000 dt_true, 0.01 at 100 dt_true.
    for (const auto& [factor, tol] : {std::pair{1000.0, 0.1}, std::pair{100.0, 0.01}}) {
        std::vector<double> theta = theta0;
        heat.apply_fixed(theta);
        for (int n = 0; n < 50; ++n) heat.implicit_euler(theta, factor * dt_true);
        for (double t : theta) {
            EXPECT_GE(t, -1e-9);
            EXPECT_LE(t, 100 + 1e-9);
        }
        const auto im = pd::time_to_reach(heat, bar.model, bar.bonds, theta0, pd::HeatIntegrator::implicit_euler,
                                          factor * dt_true, opt, 1.0, centre, 50.0);
        ASSERT_TRUE(im.reached);
        EXPECT_NEAR(im.t, cv.t, tol * cv.t) << factor << " x dt_true";
        std::printf("stiff bar: implicit Euler at %g dt_true: t50 %.9g s in %ld steps, vs CVODE %.3e\n", factor, im.t,
                    im.steps, (im.t - cv.t) / cv.t);
    }
}
