// Every problem driver rejects invalid input with exit status 2 and ONE stderr line naming the
// option (DESIGN.md, "Problem drivers"). Runs the built executables.
#include <gtest/gtest.h>

#include "pd_run_harness.hpp"
#include "scratch_dir.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>
#include <sys/wait.h>

namespace {
using Outcome = pd_test::Result;
// Runs a driver with --out in the scratch folder (pd_run_harness.hpp).
Outcome run(const std::string& exe, const std::string& args)
{
    return pd_test::run_program(exe, args, pd_test::scratch_dir() / "driver_out");
}
int lines(const std::string& s)
{
    int n = 0;
    for (char c : s) n += c == '\n';
    return n;
}
}  // namespace

TEST(DriverInputs, InvalidOptionsExitTwoWithOneLineNamingTheOption)
{
    const std::pair<const char*, const char*> cases[] = {
        {"--E -1", "--E"},          {"--E 0", "--E"},           {"--rho 0", "--rho"},
        {"--m 0", "--m"},           {"--dt-factor 0", "--dt-factor"}, {"--dt-factor -1", "--dt-factor"},
        {"--bogus 1", "--bogus"},   {"--E abc", "--E"},         {"--model fem", "--model"},
    };
    for (const char* exe : {"bar_modes_1d", "wave_block_3d"})
        for (const auto& [args, name] : cases) {
            const Outcome o = run(exe, std::string("--quick ") + args);
            EXPECT_EQ(o.status, 2) << exe << " " << args;
            EXPECT_EQ(lines(o.err), 1) << exe << " " << args << ": " << o.err;
            EXPECT_NE(o.err.find(name), std::string::npos) << exe << " " << args << ": " << o.err;
        }
    // Poisson's ratio outside (-1, 1/2) for the 3D block.
    for (const char* nu : {"0.5", "-1", "0.7"}) {
        const Outcome o = run("wave_block_3d", std::string("--quick --nu ") + nu);
        EXPECT_EQ(o.status, 2) << nu;
        EXPECT_EQ(lines(o.err), 1) << o.err;
        EXPECT_NE(o.err.find("nu"), std::string::npos) << o.err;
    }
}

TEST(DriverInputs, HelpExitsZero)
{
    for (const char* exe : {"bar_modes_1d", "wave_block_3d", "pd_run"}) EXPECT_EQ(run(exe, "--help").status, 0) << exe;
}

// large_stretch_3d: its own options (n >= 2, steps >= 1, strain > 0, tol > 0) and nu.
TEST(DriverInputs, LargeStretchRejectsInvalidOptions)
{
    const std::pair<const char*, const char*> cases[] = {
        {"--E -1", "--E"},     {"--n 1", "--n"},         {"--steps 0", "--steps"}, {"--strain 0", "--strain"},
        {"--tol -1", "--tol"}, {"--model fem", "--model"}, {"--bogus 1", "--bogus"}, {"--nu 0.5", "nu"},
    };
    for (const auto& [args, name] : cases) {
        const Outcome o = run("large_stretch_3d", std::string("--quick ") + args);
        EXPECT_EQ(o.status, 2) << args;
        EXPECT_EQ(lines(o.err), 1) << args << ": " << o.err;
        EXPECT_NE(o.err.find(name), std::string::npos) << args << ": " << o.err;
    }
    EXPECT_EQ(run("large_stretch_3d", "--help").status, 0);
}

// pals_units_3d's own options: value lists (--sf, --dx), the unit system and the grid choice.
TEST(DriverInputs, PalsUnitsListsExitTwoWithOneLineNamingTheOption)
{
    const std::pair<const char*, const char*> cases[] = {
        {"--sf 0", "--sf"},          {"--sf 0.5,abc", "--sf"},  {"--sf ,", "--sf"},     {"--dx -1e-3", "--dx"},
        {"--units km", "--units"},   {"--grid table --sf 0.5", "--grid"}, {"--rho 0", "--rho"},
        {"--t-ramp 0", "--t-ramp"},  {"--model fem", "--model"},
    };
    for (const auto& [args, name] : cases) {
        const Outcome o = run("pals_units_3d", std::string("--quick ") + args);
        EXPECT_EQ(o.status, 2) << args;
        EXPECT_EQ(lines(o.err), 1) << args << ": " << o.err;
        EXPECT_NE(o.err.find(name), std::string::npos) << args << ": " << o.err;
    }
    EXPECT_EQ(run("pals_units_3d", "--help").status, 0);
}

// Solver and integrator options of issue 3 (bar_stiffness_3d --solver/--linear, bar_modes_1d
// --integrator/--newmark-dt): invalid values exit 2 with one line naming the option.
TEST(DriverInputs, InvalidSolverOptionsExitTwo)
{
    const std::tuple<const char*, const char*, const char*> cases[] = {
        {"bar_stiffness_3d", "--solver implicit", "--solver"}, {"bar_stiffness_3d", "--linear qr", "--linear"},
        {"bar_stiffness_3d", "--newton-max-iter 0", "--newton-max-iter"},
        {"bar_modes_1d", "--integrator rk4", "--integrator"},  {"bar_modes_1d", "--newmark-dt 0", "--newmark-dt"},
        {"bar_modes_1d", "--newmark-dt -2", "--newmark-dt"},
    };
    for (const auto& [exe, args, name] : cases) {
        const Outcome o = run(exe, std::string("--quick ") + args);
        EXPECT_EQ(o.status, 2) << exe << " " << args;
        EXPECT_EQ(lines(o.err), 1) << exe << " " << args << ": " << o.err;
        EXPECT_NE(o.err.find(name), std::string::npos) << exe << " " << args << ": " << o.err;
    }
}

// The driver skeleton (pd/io/case.hpp), for every driver of drivers.txt: an --out that cannot be a
// folder (empty, an existing file) and a --threads beyond 4x the processors exit 2 with one line
// naming the option, before any computation (each call returns at once).
TEST(DriverInputs, EveryDriverRejectsUnusableOutAndThreads)
{
    std::ifstream list(std::string(PD_BIN_DIR) + "/../drivers.txt");
    std::vector<std::string> drivers;
    for (std::string exe; list >> exe;) drivers.push_back(exe);
    ASSERT_GE(drivers.size(), 20u);  // every problems/<dim>/<case>.cpp (25 when written)
    const std::string dir = pd_test::scratch_dir().string();
    std::ofstream(dir + "/a_file") << "not a folder\n";
    const std::pair<std::string, const char*> cases[] = {
        {"--out ''", "--out"}, {"--out " + dir + "/a_file", "--out"}, {"--out " + dir + "/a_file/below", "--out"},
        {"--threads 100000 --out " + dir + "/unused", "--threads"}};
    for (const std::string& exe : drivers)
        for (const auto& [args, name] : cases) {
            const std::string err_path = dir + "/err.txt";
            const std::string cmd = std::string(PD_BIN_DIR) + "/" + exe + " --quick " + args + " > /dev/null 2> " + err_path;
            const int rc = std::system(cmd.c_str());
            std::ifstream in(err_path);
            std::stringstream ss;
            ss << in.rdbuf();
            EXPECT_EQ(WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, 2) << exe << " " << args;
            EXPECT_EQ(lines(ss.str()), 1) << exe << " " << args << ": " << ss.str();
            EXPECT_NE(ss.str().find(name), std::string::npos) << exe << " " << args << ": " << ss.str();
        }
}

// Extreme but well-formed values (issue 18, findings 1 and 3) end with status 2 and one line, not a
// signal or an uncaught exception: beyond the options' magnitude range the option is named; an
// oversized lattice is refused before it is allocated (pd::require_memory names its size); a run
// needing more time steps than --max-steps (default 1e8) is refused before it loops.
TEST(DriverInputs, ExtremeValuesExitTwoWithOneLine)
{
    const std::tuple<const char*, const char*, const char*> cases[] = {
        {"prism_conductivity_3d", "--m 1e308", "--m"},         {"hourglass_modes_3d", "--m 1e308", "--m"},
        {"correspondence_heat_1d", "--length 1e308", "--length"}, {"numerical_viscosity_3d", "--delta 1e100", "--delta"},
        {"grid_orientation_2d", "--m-list=1e308", "--m-list"},  {"bar_modes_1d", "--N 2147483647", "cells"},
        {"wave_block_3d", "--t-end 1e-3 --max-steps 1000", "--max-steps"}, {"crack_branching_3d", "--t-end 1000", "--max-steps"},
    };
    for (const auto& [exe, args, name] : cases) {
        const Outcome o = run(exe, std::string("--quick ") + args);
        EXPECT_EQ(o.status, 2) << exe << " " << args << ": " << o.err;
        EXPECT_EQ(lines(o.err), 1) << exe << " " << args << ": " << o.err;
        EXPECT_NE(o.err.find(name), std::string::npos) << exe << " " << args << ": " << o.err;
    }
}

// More threads than processors run, with one warning line (oversubscription only slows a run).
TEST(DriverInputs, ThreadsAboveTheProcessorsWarn)
{
    const unsigned procs = std::thread::hardware_concurrency();
    if (procs == 0) GTEST_SKIP() << "processor count unknown";
    const Outcome o = run("sls_frequency_1d", "--quick --threads " + std::to_string(procs + 1));
    EXPECT_EQ(o.status, 0) << o.err;
    EXPECT_NE(o.err.find("warning: --threads " + std::to_string(procs + 1) + " is more than the"), std::string::npos) << o.err;
}

// --quick chooses the coarse case but never overrides a size the user gave (issue 18, finding 6):
// sls_frequency_1d's frequency grid is 17 points under --quick, --points 5 gives 5, and params.csv
// records the value that ran in both cases.
TEST(DriverInputs, QuickKeepsTheSizesTheUserGave)
{
    const std::string dir = pd_test::scratch_dir().string();
    auto count_rows = [](const std::string& path) {
        std::ifstream in(path);
        int n = -1;  // the header
        for (std::string line; std::getline(in, line);) n += !line.empty();
        return n;
    };
    auto param = [](const std::string& path, const std::string& name) {
        std::ifstream in(path);
        for (std::string line; std::getline(in, line);)
            if (line.rfind(name + ",", 0) == 0) return line.substr(name.size() + 1, line.find(',', name.size() + 1) - name.size() - 1);
        return std::string("(missing)");
    };
    for (const auto& [args, points] : {std::pair{"", 17}, std::pair{"--points 5", 5}}) {
        const std::string out = dir + "/quick_sizes";
        const std::string cmd = std::string(PD_BIN_DIR) + "/sls_frequency_1d --quick " + args + " --out " + out + " > /dev/null 2>&1";
        ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
        EXPECT_EQ(count_rows(out + "/frequency.csv"), points) << args;
        EXPECT_EQ(param(out + "/params.csv", "points"), std::to_string(points)) << args;
    }
}
