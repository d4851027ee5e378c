// The clamped, heated bar of problems/1d/thermoelastic_bar.cpp: its classical reference
// (reference/thermoelastic_bar.hpp) against closed forms, the time-dependent held temperature of the
// heat solver (HeatLoads::fixed_at) it needs, and the driver's contract.
// Closed forms: the hot end's rise r(t) is C2 (r, r' and r'' vanish at 0 and r = 1, r' = r'' = 0 at
// t_r); long after the rise the temperature is the linear profile theta = dT (1 - x/L) (exact for the
// three-point Laplacian, so T_mid = dT/2 to the integrator's tolerance) and the clamped bar carries the
// constrained stress -E alpha mean(theta) = -E alpha dT/2 at both walls.
#include "pd/core/lattice.hpp"
#include "pd/heat/agwai.hpp"
#include "pd/heat/conduction.hpp"
#include "pd/io/csv.hpp"
#include "pd/time/heat_cvode.hpp"
#include "reference/thermoelastic_bar.hpp"

#include <gtest/gtest.h>

#include "pd_run_harness.hpp"
#include "scratch_dir.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

using pd::ref::ThermoelasticBar;

TEST(ThermoelasticBarReference, HotEndRisesWithZeroFirstAndSecondDerivativesAtBothEnds)
{
    // Central differences of step h: the truncation error at an end is 10 h / tr^3 in r'' (the third
    // derivative jumps to 60/tr^3 there) and the round-off about 4 ulp(1) / h^2 near r = 1; h = 1e-5 tr
    // makes them 1e-4 and 4e-6 of 1/tr^2, below the bound 1e-3/tr^2 with or without FMA (h = 1e-6 tr
    // gave a round-off of 1.1e-3/tr^2 in the sanitize build, which has no FMA).
    const double tr = 2e-3, h = 1e-5 * tr;
    auto r = [&](double t) { return pd::ref::thermoelastic_ramp(t, tr); };
    EXPECT_EQ(r(0), 0.0);
    EXPECT_EQ(r(tr), 1.0);
    EXPECT_EQ(r(2 * tr), 1.0);
    EXPECT_NEAR(r(0.5 * tr), 0.5, 1e-15);
    for (double t : {0.0, tr}) {
        EXPECT_NEAR((r(t + h) - r(t - h)) / (2 * h), 0.0, 1e-6 / tr) << t;                 // r'
        EXPECT_NEAR((r(t + h) - 2 * r(t) + r(t - h)) / (h * h), 0.0, 1e-3 / (tr * tr)) << t;  // r''
    }
    EXPECT_EQ(pd::ref::thermoelastic_ramp(1e-9, 0), 1.0);  // t_r = 0: a step
}

TEST(ThermoelasticBarReference, ReachesTheLinearProfileAndTheConstrainedStress)
{
    // A soft, conductive bar (c = 506 m/s, L^2/kappa = 0.4 ms) after 25 diffusion times.
    const ThermoelasticBar bar{.L = 0.01, .E = 2e9, .rho = 7800, .alpha = 1e-5, .k = 1e6, .c = 500, .dT = 50, .ramp = 2e-3, .cells = 20};
    const std::vector<double> t_out{0.0, 0.005, 0.01};
    const double sigma = -bar.E * bar.alpha * bar.dT / 2;
    // Bounds: T_mid is the steady profile to the integrators' accuracy (exp(-25 pi^2) of the transient is
    // gone); the stress keeps the small undamped ringing the 2 ms rise leaves, bounded here by 1e-4 of sigma.
    for (bool mri : {true, false}) {
        const auto h = mri ? pd::ref::thermoelastic_bar_mri(bar, t_out, 1.0) : pd::ref::thermoelastic_bar_cvode(bar, t_out, 1e-9);
        ASSERT_EQ(h.t_s.size(), 3u);
        EXPECT_EQ(h.stress_left[0], 0.0);
        EXPECT_NEAR(h.t_s.back(), 0.01, 1e-15);
        EXPECT_NEAR(h.T_mid.back(), bar.dT / 2, 1e-6 * bar.dT) << (mri ? "MRIStep" : "CVODE");
        EXPECT_NEAR(h.stress_left.back(), sigma, 1e-4 * std::abs(sigma)) << (mri ? "MRIStep" : "CVODE");
        EXPECT_NEAR(h.stress_right.back(), sigma, 1e-4 * std::abs(sigma)) << (mri ? "MRIStep" : "CVODE");
    }
    EXPECT_THROW(pd::ref::thermoelastic_bar_mri({.L = 0.01, .E = 2e9, .rho = 7800, .alpha = 1e-5, .k = 1, .c = 500, .dT = 1, .ramp = 0, .cells = 5},
                                                t_out),
                 std::invalid_argument);  // odd cell count
}

// Held temperatures that follow fixed_at(f, t): set at the end of each step by explicit and implicit
// Euler; CVODE refuses them.
TEST(Heat, HeldTemperaturesFollowFixedAtTheEndOfEachStep)
{
    const double dx = 1e-3, A = 1e-4;
    const pd::Body<1> body = pd::box<1>({0.0}, {20 * dx}, dx, A);
    const pd::Bonds bonds = pd::build_bonds(body, 3 * dx);
    pd::HeatLoads loads;
    loads.fixed = {0}, loads.fixed_value = {-1};  // ignored once fixed_at is set
    loads.fixed_at = [](std::size_t, double t) { return 1e3 * t; };
    const double dt = 1e-3;
    for (auto integrator : {pd::HeatIntegrator::explicit_euler, pd::HeatIntegrator::implicit_euler}) {
        auto field = pd::make_temperature_field(pd::Agwai({.k = 50, .measure = A}, body, bonds), bonds, std::vector<double>(body.size(), 3.9e6),
                                                loads, std::vector<double>(body.size(), 0.0), integrator, dt);
        EXPECT_EQ(field->theta[0], 0.0);  // t = 0
        for (int n = 1; n <= 5; ++n) {
            field->advance();
            EXPECT_DOUBLE_EQ(field->theta[0], 1e3 * n * dt) << pd::name(integrator) << " step " << n;
        }
        EXPECT_GT(field->theta[1], 0.0);  // heat flows in from the rising end
    }
    EXPECT_THROW(pd::make_temperature_field(pd::Agwai({.k = 50, .measure = A}, body, bonds), bonds, std::vector<double>(body.size(), 3.9e6),
                                            loads, std::vector<double>(body.size(), 0.0), pd::HeatIntegrator::cvode, dt),
                 std::invalid_argument);
}

// A small run of the driver writes its rows; bad input exits 2 with one line.
TEST(ThermoelasticBarDriver, SmallRunWritesItsRowsAndBadInputExitsTwo)
{
    const auto dir = pd_test::scratch_dir() / "thermoelastic_bar";
    const pd_test::Result r =
        pd_test::run_program("thermoelastic_bar_1d", "--model pmb --N 20 --ref-cells 20 --t-end 1e-3 --nsync-mk 10", dir);
    ASSERT_EQ(r.status, 0) << r.err;
    const auto summary = pd::io::read_csv(dir / "summary.csv");
    std::vector<std::string> names;
    for (const auto& row : summary.rows) names.push_back(row.fields.at(0));
    for (const char* q : {"stress_end", "T_mid", "pmb_nsync_max_stable"})
        EXPECT_NE(std::find(names.begin(), names.end(), q), names.end()) << q;
    const auto ns = pd::io::read_csv(dir / "nsync.csv");
    EXPECT_EQ(ns.rows.size(), 2u);  // the monolithic run and N_sync 10
    for (const char* args : {"--N 21", "--ref-cells 7", "--k 0", "--model fem", "--nsync-mk -1"}) {
        const pd_test::Result bad = pd_test::run_program("thermoelastic_bar_1d", args, dir);
        EXPECT_EQ(bad.status, 2) << args;
        EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << args << ": " << bad.err;
    }
}
