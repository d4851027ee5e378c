// tests/test_pd_run_thermal_expansion.cpp -- --alpha / --T-ref of build/bin/pd_run (thermal expansion of
// PMB, LPS and correspondence from the run's temperatures). References: a free cube held at y = x with the uniform
// temperature T_ref + dT starts with the strain energy of a fully constrained body, 9/2 K (alpha dT)^2
// per unit volume at every point (closed form; spec/000a V7), keeps its total energy and expands;
// T = T_ref gives the files of a run without --alpha byte for byte; --thermal-strain bond-mean leaves a
// free cube under a linear temperature field force-free; the input contracts.
#include "pd/io/csv.hpp"

#include <gtest/gtest.h>

#include "pd_run_harness.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

using pd::io::read_csv;
using pd_test::lattice_csv;
using pd_test::num;
using pd_test::pd_run;
using pd_test::Result;
using pd_test::slurp;
using pd_test::write_file;

namespace {
constexpr double dx = 1e-3, E = 200e9, nu = 0.25, alpha = 1.2e-5, T_ref = 20, dT = 50;  // K = E / (3 (1 - 2 nu))
const std::string heat = " --heat agwai --k 50 --cv 500 --E 200e9 --nu 0.25 --rho 7800 --delta 3e-3";

std::string cube(double T0)
{
    const std::string t = num(T0);
    return write_file(std::string("cube_").append(t).append(".csv"),
                      lattice_csv(6, dx, ",T0", [&](int, int, int) { return std::string(",").append(t); }))
        .string();
}
}  // namespace

// The free expansion u_s = eps (x - c) is the static solution (no force at y = x + u_s), so from rest
// each mode's amplitude follows q_s (1 - cos omega t): the projection P(t) = sum (x - c).u / (eps
// sum |x - c|^2) (equal point masses) stays in [0, 2] and is > 0 once it moves. dt = 1e-8 s (about
// 0.1 of the stable step) keeps Verlet's energy error below 1e-3 of W0. LPS, PALS, correspondence with
// the linear law (the thermal strain) and with Flanagan-Taylor (its increment at the first update).
TEST(PdRunThermalExpansion, HeatedFreeCubeStartsWithTheConstrainedEnergyAndExpands)
{
    for (const std::string model : {"lps", "pals", "correspondence", "correspondence --stress-law flanagan-taylor"}) {
        const Result r = pd_run("te_" + model.substr(0, 4) + std::to_string(model.size()),
                                "--input " + cube(T_ref + dT) + heat + " --model " + model + " --alpha " + num(alpha) + " --T-ref " +
                                    num(T_ref) + " --dt 1e-8 --steps 300 --energy-every 10 --output-steps 100,200,300");
        ASSERT_EQ(r.status, 0) << r.err;
        const auto energy = read_csv(r.dir / "energy.csv");
        const double K = E / (3 * (1 - 2 * nu)), eps = alpha * dT, W0 = 4.5 * K * eps * eps * 216 * dx * dx * dx;
        EXPECT_NEAR(energy.number(0, 3), W0, 1e-10 * W0) << model;  // strain_J at step 0
        EXPECT_EQ(energy.number(0, 2), 0.0);                // kinetic_J: at rest
        for (std::size_t q = 1; q < energy.rows.size(); ++q) EXPECT_NEAR(energy.number(q, 5), W0, 1e-3 * W0) << "row " << q;  // total_J
        const double c = 3 * dx;  // centre of the cube
        for (const char* f : {"state_step0100.csv", "state_step0200.csv", "state_step0300.csv"}) {
            const auto st = read_csv(r.dir / f);  // node_id, x, y, z, ux, uy, uz, ...
            double proj = 0, norm2 = 0;
            for (std::size_t i = 0; i < st.rows.size(); ++i)
                for (int d = 0; d < 3; ++d) {
                    const double xc = st.number(i, 1 + d) - c;
                    proj += xc * st.number(i, 4 + d), norm2 += xc * xc;
                }
            const double P = proj / (eps * norm2);
            EXPECT_GT(P, 0.01) << f;
            EXPECT_LT(P, 2.0) << f;
        }
    }
}

// At T = T_ref the thermal strain is zero: every file equals that of the run without --alpha.
TEST(PdRunThermalExpansion, ReferenceTemperatureChangesNothing)
{
    for (const char* model : {"pmb", "lps", "correspondence"}) {
        const std::string in = "--input " + cube(T_ref) + heat + " --model " + model + " --steps 20 --output-steps 20 --s0 1e-3";
        const Result a = pd_run(std::string("te_ref_a_") + model, in);
        const Result b = pd_run(std::string("te_ref_b_") + model, in + " --alpha " + num(alpha) + " --T-ref " + num(T_ref));
        ASSERT_EQ(a.status, 0) << a.err;
        ASSERT_EQ(b.status, 0) << b.err;
        for (const char* f : {"state_step0020.csv", "energy.csv", "heat.csv"})
            EXPECT_EQ(slurp(a.dir / f), slurp(b.dir / f)) << model << " " << f;
    }
}

// A linear temperature field T = T_ref + (eps0 + a X) / alpha with the compatible displacement of that
// free thermal strain (tests/test_thermal_bond_mean.cpp, linear_temperature_field) as the cloud's initial
// ux, uy, uz: classical thermoelasticity has no stress, and with the bond mean each bond's mechanical
// extension is of second order in a X (|W|^2 / 2 <= 3e-9 of its length here, |W| <= a |X| = 7e-5),
// against the owner rule's surface strains of order a delta / 2 = 3e-5: an energy ratio ~1e-8, below
// the bound 1e-6. The owner rule's surface nodes see their own temperature only.
TEST(PdRunThermalExpansion, BondMeanLeavesALinearTemperatureFieldForceFree)
{
    const double eps0 = alpha * dT, a = alpha * 10 / (6 * dx), c = 3 * dx;  // [-], [1/m]: 10 K across the cube, [m]
    const std::string cloud = write_file("cube_linear.csv", lattice_csv(6, dx, ",ux,uy,uz,T0", [&](int i, int j, int k) {
        const double X = (i + 0.5) * dx - c, Y = (j + 0.5) * dx - c, Z = (k + 0.5) * dx - c, eps = eps0 + a * X;
        return "," + num(eps0 * X + 0.5 * a * (X * X - Y * Y - Z * Z)) + "," + num(eps * Y) + "," + num(eps * Z) + "," + num(T_ref + eps / alpha);
    })).string();
    for (const char* model : {"lps", "lps-scf", "pals"}) {
        double W0[2];
        for (int mean = 0; mean < 2; ++mean) {
            const Result r = pd_run(std::string("te_lin_") + model + std::to_string(mean),
                                    "--input " + cloud + heat + " --model " + model + " --alpha " + num(alpha) + " --T-ref " + num(T_ref) +
                                        " --steps 1 --output-steps none" + (mean ? " --thermal-strain bond-mean" : ""));
            ASSERT_EQ(r.status, 0) << r.err;
            W0[mean] = read_csv(r.dir / "energy.csv").number(0, 3);  // strain_J at step 0
        }
        EXPECT_GT(W0[0], 0) << model;
        EXPECT_LT(W0[1], 1e-6 * W0[0]) << model << ": bond mean " << W0[1] << " J, owner " << W0[0] << " J";
    }
}

TEST(PdRunThermalExpansion, BadInputsExitTwoWithOneLine)
{
    const std::string in = "--input " + cube(T_ref + dT) + " --steps 5";
    const std::string steel = " --E 200e9 --nu 0.25 --rho 7800 --delta 3e-3";
    std::string flat = "x,y,z,volume,T0\n";  // a 6 x 6 plate for --dim 2
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i) flat += num((i + 0.5) * dx) + "," + num((j + 0.5) * dx) + ",0," + num(dx * dx) + ",70\n";
    const std::filesystem::path plate = write_file("plate_70.csv", flat);
    struct Case { std::string args, expect; };
    const std::vector<Case> cases = {
        {in + steel + " --alpha 1e-5 --T-ref 20", "--alpha needs --heat"},
        {in + heat + " --alpha 1e-5", "--T-ref is required with --alpha"},
        {in + heat + " --T-ref 20", "--T-ref needs --alpha"},
        {in + heat + " --thermal-strain bond-mean", "--thermal-strain needs --alpha"},
        {in + heat + " --model correspondence --alpha 1e-5 --T-ref 20 --thermal-strain bond-mean", "bond_mean is for the ordinary models"},
        {"--input " + cube(T_ref) + " --heat agwai --k 50 --cv 500 --rho 7800 --delta 3e-3 --mechanics off --alpha 1e-5 --T-ref 20",
         "--alpha needs the mechanics"},
        {"--input " + plate.string() + " --steps 5" + heat + " --dim 2 --plane strain --model correspondence --alpha 1e-5 --T-ref 20",
         "plane strain"},
    };
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const Result r = pd_run("te_bad" + std::to_string(k), cases[k].args);
        EXPECT_EQ(r.status, 2) << cases[k].args;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_NE(r.err.find(cases[k].expect), std::string::npos) << cases[k].args << "\n" << r.err;
    }
}
