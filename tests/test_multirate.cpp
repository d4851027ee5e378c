// The clocks of a multirate run (time/multirate.hpp) against hand-counted cases of the rule of
// spec/000a sec. 3.3.4, and its guarantees (both clocks stable, whole sub-multiples) over a sweep.
#include "pd/time/multirate.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <stdexcept>

using namespace pd;

// T = 1 s, mechanical bound 3 ms, thermal bound 0.1 s: N = ceil(333.3) = 334, N_T = 10,
// N_sync(MK) = floor(334/10) = 33, N rounded up to 11 x 33 = 363.
TEST(Multirate, ChoosesTheSyncFromBothBounds)
{
    const MultirateSteps s = multirate_steps(1.0, 3e-3, 0.1);
    EXPECT_EQ(s.nsync_mk, 33);
    EXPECT_EQ(s.mech_steps, 363);
    EXPECT_DOUBLE_EQ(s.dt_mech, 1.0 / 363);
    EXPECT_DOUBLE_EQ(s.dt_thermal, 33.0 / 363);
    EXPECT_EQ(s.nsync_mh, 0);
    EXPECT_EQ(s.dt_heat, 0.0);
}

// With heat generation every 10 steps: N a multiple of lcm(33, 10) = 330, i.e. 660.
TEST(Multirate, HeatGenerationStepIsASubMultipleToo)
{
    const MultirateSteps s = multirate_steps(1.0, 3e-3, 0.1, 10);
    EXPECT_EQ(s.nsync_mk, 33);
    EXPECT_EQ(s.mech_steps, 660);
    EXPECT_DOUBLE_EQ(s.dt_heat, 10.0 / 660);
}

// A given N_sync(MK) is kept: N = 334 rounded up to a multiple of 94 = 376.
TEST(Multirate, KeepsAGivenSync)
{
    const MultirateSteps s = multirate_steps(1.0, 3e-3, 0.5, 0, 94);
    EXPECT_EQ(s.nsync_mk, 94);
    EXPECT_EQ(s.mech_steps, 376);
    EXPECT_THROW(multirate_steps(1.0, 3e-3, 0.1, 0, 94), std::invalid_argument);  // 94/376 s > 0.1 s
}

// Thermal bound below the mechanical one: the mechanical step takes it, one thermal step per step.
TEST(Multirate, ThermalBoundSmallerThanMechanical)
{
    const MultirateSteps s = multirate_steps(1.0, 0.1, 0.03);
    EXPECT_EQ(s.nsync_mk, 1);
    EXPECT_EQ(s.mech_steps, 34);
}

// A duration of a whole number of bounds keeps that number (no extra step from round-off).
TEST(Multirate, WholeNumberOfStepsStays)
{
    EXPECT_EQ(multirate_steps(1.0, 0.01, 0.01).mech_steps, 100);
    EXPECT_EQ(multirate_steps(0.3, 0.1, 1.0).mech_steps, 3);
}

TEST(Multirate, BothClocksStableAndWholeOverASweep)
{
    for (double dm : {1e-9, 3.7e-9, 2.65e-8, 1e-6})
        for (double ratio : {0.5, 1.0, 1.7, 94.3, 1e4, 1e6})
            for (long mh : {0L, 1L, 7L, 100L}) {
                const double T = 250e-6, dth = ratio * dm;
                if (T / std::min(dm, dth) > 1e9) continue;
                const MultirateSteps s = multirate_steps(T, dm, dth, mh);
                EXPECT_LE(s.dt_mech, dm * (1 + 1e-12)) << dm << " " << ratio;
                EXPECT_LE(s.dt_thermal, dth * (1 + 1e-12)) << dm << " " << ratio;
                EXPECT_EQ(s.mech_steps % s.nsync_mk, 0);
                if (mh > 0) {
                    EXPECT_EQ(s.mech_steps % mh, 0);
                }
                EXPECT_NEAR(s.dt_mech * double(s.mech_steps), T, 1e-12 * T);
                // no more steps than needed: one multiple of the sync period fewer would break a bound
                const long period = mh > 0 ? std::lcm(s.nsync_mk, mh) : s.nsync_mk;
                EXPECT_GT(T / double(s.mech_steps - period), std::min(dm, dth) * (1 - 1e-12)) << dm << " " << ratio;
            }
}

TEST(Multirate, RefusesBadInput)
{
    EXPECT_THROW(multirate_steps(0, 1e-3, 1e-2), std::invalid_argument);
    EXPECT_THROW(multirate_steps(1, 0, 1e-2), std::invalid_argument);
    EXPECT_THROW(multirate_steps(1, 1e-3, -1), std::invalid_argument);
    EXPECT_THROW(multirate_steps(1, 1e-3, 1e-2, -1), std::invalid_argument);
}
