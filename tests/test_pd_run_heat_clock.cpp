// tests/test_pd_run_heat_clock.cpp -- --nsync-mk and --heat-source of build/bin/pd_run. References:
// an insulated cloud under a uniform source s rises uniformly by s t/(rho cv) (closed form; the heat
// flow between equal temperatures is zero), so heat.csv's T_min = T_max = T0 + s t/(rho cv) and
// heat_J grows by s V t; with --nsync-mk N one thermal step of N dt is taken every N mechanical steps.
#include "pd/io/csv.hpp"

#include <gtest/gtest.h>

#include "pd_run_harness.hpp"

#include <algorithm>
#include <string>
#include <vector>

using pd::io::read_csv;
using pd_test::lattice_csv;
using pd_test::num;
using pd_test::pd_run;
using pd_test::Result;
using pd_test::write_file;

namespace {
constexpr double dx = 1e-3, rho = 7800, cv = 500, T0 = 300, s = 3.9e9, dt = 1e-8;  // s: 1 K per ms at rho cv = 3.9e6
const std::string heat_only = " --rho 7800 --delta 3e-3 --heat agwai --k 50 --cv 500";
const std::string material = " --E 200e9 --nu 0.25" + heat_only;

std::string cube()
{
    return write_file("cube_clock.csv", lattice_csv(5, dx, "", [](int, int, int) { return std::string(); })).string();
}
}  // namespace

TEST(PdRunHeatClock, UniformSourceHeatsAnInsulatedCloudAtSOverRhoCv)
{
    for (const char* integrator : {"explicit", "implicit"}) {
        const Result r = pd_run(std::string("clock_src_") + integrator, "--input " + cube() + heat_only + " --T0 300 --mechanics off --thermal-steps 40" +
                                                                            " --dt-thermal 1e-4 --heat-source " + num(s) + " --thermal-integrator " +
                                                                            integrator);
        ASSERT_EQ(r.status, 0) << r.err;
        const auto heat = read_csv(r.dir / "heat.csv");  // thermal_step, t_s, heat_J, T_min, T_max
        const std::size_t last = heat.rows.size() - 1;
        const double t = heat.number(last, 1), rise = s * t / (rho * cv);
        EXPECT_NEAR(t, 40 * 1e-4, 1e-15);
        EXPECT_NEAR(heat.number(last, 3), T0 + rise, 1e-9 * T0) << integrator;
        EXPECT_NEAR(heat.number(last, 4), T0 + rise, 1e-9 * T0) << integrator;
        EXPECT_NEAR(heat.number(last, 2) - heat.number(0, 2), s * 125 * dx * dx * dx * t, 1e-9 * heat.number(0, 2)) << integrator;
    }
}

TEST(PdRunHeatClock, NsyncMkTakesOneThermalStepOfNMechanicalSteps)
{
    const Result r = pd_run("clock_nsync", "--input " + cube() + material + " --T0 300 --dt " + num(dt) + " --steps 30 --nsync-mk 6 --heat-source " +
                                               num(s) + " --energy-every 1");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto heat = read_csv(r.dir / "heat.csv");
    ASSERT_EQ(heat.rows.size(), 6u);  // thermal steps 0 .. 5
    for (std::size_t q = 0; q < heat.rows.size(); ++q) {
        EXPECT_EQ(heat.number(q, 0), double(q));
        EXPECT_NEAR(heat.number(q, 1), q * 6 * dt, 1e-20);
        EXPECT_NEAR(heat.number(q, 4), T0 + s * q * 6 * dt / (rho * cv), 1e-9 * T0);
    }
}

TEST(PdRunHeatClock, BadInputsExitTwoWithOneLine)
{
    const std::string in = "--input " + cube() + " --steps 5";
    struct Case { std::string args, expect; };
    const std::vector<Case> cases = {
        {in + material + " --T0 300 --nsync-mk 0", "--nsync-mk must be >= 1"},
        {in + material + " --T0 300 --nsync-mk 5 --dt-thermal 1e-6", "exclude each other"},
        {"--input " + cube() + heat_only + " --T0 300 --mechanics off --nsync-mk 5", "--nsync-mk needs the mechanics"},
        {in + " --E 200e9 --nu 0.25 --rho 7800 --delta 3e-3 --heat-source 1e9", "--heat-source needs --heat"},
        {in + material + " --T0 300 --heat-source 1e9 --thermal-integrator cvode", "--heat-source is written for"},
        {in + material + " --T0 300 --heat-source inf", "--heat-source"},
    };
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const Result r = pd_run("clock_bad" + std::to_string(k), cases[k].args);
        EXPECT_EQ(r.status, 2) << cases[k].args;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_NE(r.err.find(cases[k].expect), std::string::npos) << cases[k].args << "\n" << r.err;
    }
}
