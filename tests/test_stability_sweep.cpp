// The stability sweep finds the von Neumann limit of velocity Verlet on a linear oscillator:
// for omega = 1 the scheme is stable for dt < 2 / omega and unstable beyond (closed form); the ladder of
// the unconditionally stable schemes stops at the first unstable factor.
#include "problems/common/stability_sweep.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/verlet.hpp"

#include <gtest/gtest.h>

using namespace pd;

namespace {
// Two nodes 1 m apart, node 0 fixed, PMB 1D, delta = 1, A = V = 1, E = 1/2, rho = 1: omega = 1
// (see test_damage_time.cpp). Runs 400 steps of dt = factor (dt_crit = 1 s here).
io::StabilityPoint run_oscillator(double factor)
{
    Body<1> body = box<1>({{0}}, {{2.0}}, 1.0, 1.0);
    Bonds bonds = build_bonds(body, 1.0);
    PMB pmb{{Elastic::from_E_nu(0.5, 0.25), 1, Plane::stress, 1.0}, bonds};
    Explicit<1, PMB> run{body, bonds, pmb, 1.0};
    run.u.c[0][1] = 1e-3;
    run.boundary.fix({0});
    run.start();
    io::StabilityPoint p{factor, factor, 1.0};
    double e_max = run.initial_energy();
    try {
        run.advance(400, factor, 1, [&](const Energies& e) { e_max = std::max(e_max, e.kinetic + e.strain); });
    } catch (const Unstable& u) {
        p.stable = false;
        p.unstable_step = u.step;
    }
    p.energy_growth = e_max / run.initial_energy();
    return p;
}
}  // namespace

TEST(StabilitySweep, FindsVerletLimitOfOscillator)
{
    const auto r = io::stability_sweep({0.5, 1.0, 1.5, 2.5}, run_oscillator, 8.0, 0.005);
    // Bracket below 0.5 % of the threshold; just above 2 the growth per step is ~sqrt(2 eps),
    // enough to exceed 10x in 400 steps for eps >= 0.5 %: the threshold lies in [2, 2.015].
    EXPECT_GE(r.threshold, 1.995);
    EXPECT_LE(r.threshold, 2.015);
    EXPECT_TRUE(r.points[0].stable);
    EXPECT_FALSE(r.points[3].stable);
    EXPECT_GT(r.points[3].unstable_step, 0);
}

TEST(StabilitySweep, AllStableDoublesUntilUnstableAndNoThresholdIfNone)
{
    const auto r = io::stability_sweep({0.5}, run_oscillator, 8.0, 0.01);  // 0.5 -> 1 -> 2 -> 4
    EXPECT_NEAR(r.threshold, 2.0, 0.03);
    const auto none = io::stability_sweep({0.1}, run_oscillator, 1.0, 0.01);  // never beyond 1
    EXPECT_TRUE(std::isnan(none.threshold));
}

TEST(StabilitySweep, AllUnstableHalvesUntilStableWhenAllowed)
{
    const auto r = io::stability_sweep({6.0}, run_oscillator, 8.0, 0.01, 0.1);  // 6 -> 3 -> 1.5, then bisection
    EXPECT_NEAR(r.threshold, 2.0, 0.03);
    EXPECT_EQ(r.points[2].dt_factor, 1.5);
    const auto old = io::stability_sweep({6.0}, run_oscillator, 8.0, 0.01);  // no min_factor: no search downwards
    EXPECT_TRUE(std::isnan(old.threshold));
    EXPECT_EQ(old.points.size(), 1u);
}

TEST(StabilitySweep, LadderStopsAtTheFirstUnstableFactor)
{
    bool bracketed = true;
    const auto r = io::stability_ladder({0.5, 1.0, 1.9, 2.5, 3.0}, run_oscillator, bracketed);  // Verlet: unstable beyond 2
    EXPECT_EQ(r.threshold, 1.9);
    EXPECT_TRUE(bracketed);
    ASSERT_EQ(r.points.size(), 4u);  // 3.0 is not run
    EXPECT_FALSE(r.points.back().stable);
    const auto below = io::stability_ladder({0.5, 1.0}, run_oscillator, bracketed);
    EXPECT_EQ(below.threshold, 1.0);  // a lower bound only: nothing failed
    EXPECT_FALSE(bracketed);
}
