// tests/test_pd_run_dissipation.cpp -- the inelastic models of build/bin/pd_run (--plasticity,
// --viscoelastic) and the release of their heat (--beta-tq, --nsync-mh). References, none from the
// code under test:
// - energy: a free cube has no external work, so the mechanical energy it loses (energy.csv
//   kinetic_J + strain_J) is what the dissipation took; beta_TQ of it (plastic) or all of it (viscous)
//   must appear as heat (heat.csv heat_J = sum rho cv V T; insulated conduction keeps the sum);
// - bookkeeping (spec/000a V9, eqs. 3.22-3.24): a release at mechanical step m (every N_sync(MH)
//   steps, before the thermal steps due after m are logged) adds the heat generated up to step m - 1,
//   so heat.csv's rise at thermal step n is energy.csv's dissipated_heat_J of step m - 1, m the last
//   release before n;
// - Johnson-Cook softening: (A + B ep^n)(1 - theta*) at theta* = 1/2 is the law with A/2, B/2 at
//   theta_ref, so both runs are the same to round-off (the temperature reaches the law).
#include "pd/io/csv.hpp"

#include <gtest/gtest.h>

#include "pd_run_harness.hpp"

#include <string>

using pd::io::read_csv;
using pd_test::lattice_csv;
using pd_test::num;
using pd_test::pd_run;
using pd_test::Result;
using pd_test::write_file;

namespace {
constexpr int n = 8;
constexpr double dx = 1e-3;

// 8^3 steel cube stretched along x and contracted across at t = 0 (v = (5000 x, -1500 y, -1500 z) 1/s
// about its centre): the deviatoric strain passes the yield strain 1e-3 within a few steps.
std::string stretched_cube(double T0)
{
    const double c = n * dx / 2;
    auto v = [&](int i, int j, int k) {
        return "," + num(5000 * ((i + 0.5) * dx - c)) + "," + num(-1500 * ((j + 0.5) * dx - c)) + "," + num(-1500 * ((k + 0.5) * dx - c)) + "," +
               num(T0);
    };
    return write_file("stretched_" + num(T0) + ".csv", lattice_csv(n, dx, ",vx,vy,vz,T0", v)).string();
}

// k = 1 W/(m K): the heat stays where it is made over these 1e-5 s; one thermal step per mechanical step.
const std::string scene = " --E 200e9 --nu 0.3 --rho 7800 --delta 3.015e-3 --heat agwai --k 1 --cv 500 --nsync-mk 1";
const std::string jc = " --plasticity johnson-cook --jc-A 2e8 --jc-B 5e8 --jc-n 0.5";

// Kinetic + strain energy of row q of energy.csv [J].
double mechanical(const pd::io::CsvTable& e, std::size_t q) { return e.number(q, 2) + e.number(q, 3); }

struct Books {
    double lost = 0, heat = 0, kinetic0 = 0;  // mechanical energy lost, heat gained, initial kinetic [J]
};
Books books(const Result& r)
{
    const auto e = read_csv(r.dir / "energy.csv");  // step, t_s, kinetic_J, strain_J, ...
    const auto h = read_csv(r.dir / "heat.csv");    // thermal_step, t_s, heat_J, T_min, T_max
    return {mechanical(e, 0) - mechanical(e, e.rows.size() - 1), h.number(h.rows.size() - 1, 2) - h.number(0, 2), e.number(0, 2)};
}
}  // namespace

TEST(PdRunDissipation, PlasticHeatIsBetaOfTheMechanicalEnergyLost)
{
    for (const std::string model : {"lps", "pals", "correspondence"}) {
        const Result r = pd_run("dis_plastic_" + model, "--input " + stretched_cube(300) + scene + jc + " --model " + model +
                                                            " --beta-tq 0.5 --steps 400 --energy-every 20");
        ASSERT_EQ(r.status, 0) << r.err;
        const Books b = books(r);
        EXPECT_GT(b.lost, 0.5 * b.kinetic0) << model;  // the plastic flow took most of the motion
        // Measured 0.80 % (lps), 0.97 % (pals, correspondence) above 1/2: the return's dissipation over a
        // step, first order in dt (lps: 0.32 % at dt/2, 0.13 % at dt/4); bound 3 %.
        EXPECT_NEAR(b.heat / b.lost, 0.5, 0.03 * 0.5) << model;
        const auto state = read_csv(r.dir / "state_step0400.csv");
        double ep_max = 0;
        for (std::size_t q = 0; q < state.rows.size(); ++q) ep_max = std::max(ep_max, state.number(q, state.column("ep")));
        EXPECT_GT(ep_max, 1e-3) << model;  // the state file carries the plastic strain
    }
}

TEST(PdRunDissipation, ViscousHeatIsTheMechanicalEnergyLost)
{
    for (const std::string model : {"lps", "correspondence --stress-law flanagan-taylor"}) {
        const Result r = pd_run("dis_viscous_" + model.substr(0, 4), "--input " + stretched_cube(300) + scene + " --model " + model +
                                                                         " --viscoelastic sls --sls-gamma 1 --sls-tau 5e-6 --steps 400");
        ASSERT_EQ(r.status, 0) << r.err;
        const Books b = books(r);
        EXPECT_GT(b.lost, 0.5 * b.kinetic0) << model;
        // Measured 2e-4 (lps) and 2.2e-3 (correspondence) above 1 (the Verlet energy error; the dashpot
        // integral is exact per step for a linear history); bound 1 %.
        EXPECT_NEAR(b.heat / b.lost, 1.0, 0.01) << model;
    }
}

TEST(PdRunDissipation, EachReleaseAddsTheHeatGeneratedBeforeItsStep)
{
    for (const int nsync : {1, 7, 0}) {
        const Result r = pd_run("dis_books_" + std::to_string(nsync), "--input " + stretched_cube(300) + scene + jc +
                                                                          " --model correspondence --beta-tq 0.5 --steps 60 --energy-every 1 --nsync-mh " +
                                                                          std::to_string(nsync));
        ASSERT_EQ(r.status, 0) << r.err;
        const auto e = read_csv(r.dir / "energy.csv"), h = read_csv(r.dir / "heat.csv");
        ASSERT_EQ(e.rows.size(), 61u);
        ASSERT_EQ(h.rows.size(), 61u);
        const std::size_t generated = e.column("dissipated_heat_J");
        EXPECT_GT(e.number(60, generated), 0.1 * mechanical(e, 0)) << nsync;
        for (std::size_t q = 0; q < h.rows.size(); ++q) {
            long release = 0;  // the last release before thermal step q (0: none)
            for (long m = 1; m < long(q); ++m)
                if (nsync > 0 && m % nsync == 0) release = m;
            const double expected = release > 0 ? e.number(release - 1, generated) : 0.0;
            // Sums of 512 terms near 600 J: round-off ~1e-12 J (measured 2.6e-12); bound 1e-12 of heat_J.
            EXPECT_NEAR(h.number(q, 2) - h.number(0, 2), expected, 1e-12 * h.number(0, 2)) << "nsync " << nsync << ", thermal step " << q;
        }
    }
}

TEST(PdRunDissipation, JohnsonCookSofteningReadsTheRunsTemperatures)
{
    const std::string soft = scene + " --model lps --plasticity johnson-cook --jc-n 0.5 --jc-m 1 --jc-T-ref 300 --jc-T-melt 1300 --beta-tq 0" +
                             " --steps 200 --energy-every 10";
    const Result hot = pd_run("dis_soft_hot", "--input " + stretched_cube(800) + soft + " --jc-A 2e8 --jc-B 5e8");
    const Result half = pd_run("dis_soft_half", "--input " + stretched_cube(300) + soft + " --jc-A 1e8 --jc-B 2.5e8");
    const Result cold = pd_run("dis_soft_cold", "--input " + stretched_cube(300) + soft + " --jc-A 2e8 --jc-B 5e8");
    for (const Result* r : {&hot, &half, &cold}) ASSERT_EQ(r->status, 0) << r->err;
    const auto a = read_csv(hot.dir / "energy.csv"), b = read_csv(half.dir / "energy.csv"), c = read_csv(cold.dir / "energy.csv");
    const std::size_t last = a.rows.size() - 1;
    for (std::size_t q = 0; q <= last; ++q)
        for (const std::size_t col : {2u, 3u})  // measured identical; bound: round-off of the two products, far below the 10 % of c
            EXPECT_NEAR(a.number(q, col), b.number(q, col), 1e-12 * mechanical(a, 0)) << q;
    EXPECT_GT(std::abs(c.number(last, 2) - a.number(last, 2)), 0.1 * a.number(last, 2));  // without softening: another motion
}

TEST(PdRunDissipation, PlasticModelsTakeTheThermalStrainOfTheirElasticModel)
{
    // A cube 100 K above T_ref, at rest: alpha (T - T_ref) = 1e-3 of free expansion, isotropic, so the
    // deviatoric extension stays below the yield strain A/(3G) = 4e-3: no flow, and the plastic models
    // move as their elastic ones (PlasticLPS, PlasticPALS: the same formulas at e_dp = 0, summed in
    // another order: measured 2.3e-14 of the strain energy; bound 1e-12).
    const std::string cube = write_file("warm_cube.csv", lattice_csv(n, dx, ",T0", [](int, int, int) { return std::string(",400"); })).string();
    const std::string args = "--input " + cube + scene + " --alpha 1e-5 --T-ref 300 --steps 100 --energy-every 10 --model ";
    for (const std::string model : {"lps", "pals"}) {
        const Result elastic = pd_run("dis_warm_" + model, args + model);
        const Result plastic = pd_run("dis_warm_plastic_" + model, args + model + " --plasticity johnson-cook --jc-A 2e9");
        ASSERT_EQ(elastic.status, 0) << elastic.err;
        ASSERT_EQ(plastic.status, 0) << plastic.err;
        const auto a = read_csv(elastic.dir / "energy.csv"), b = read_csv(plastic.dir / "energy.csv");
        EXPECT_GT(a.number(0, 3), 0) << model;  // the held-back expansion is strain energy at step 0
        for (std::size_t q = 0; q < a.rows.size(); ++q)
            for (const std::size_t col : {2u, 3u}) EXPECT_NEAR(a.number(q, col), b.number(q, col), 1e-12 * a.number(0, 3)) << model << " row " << q;
        EXPECT_EQ(b.number(b.rows.size() - 1, b.column("dissipated_J")), 0.0) << model;  // no plastic work
    }
}

TEST(PdRunDissipation, BadInputsExitTwoWithOneLine)
{
    const std::string cube = "--input " + stretched_cube(300) + scene + " --steps 2";
    const std::pair<std::string, std::string> cases[] = {
        {" --model pmb" + jc, "--plasticity applies to --model lps"},
        {" --model lps --plasticity johnson-cook", "--jc-A is required"},
        {" --model lps" + jc + " --viscoelastic sls --sls-tau 1e-6", "exclude each other"},
        {" --model lps" + jc + " --beta-tq 1.5", "--beta-tq must lie in [0, 1]"},
        {" --model lps" + jc + " --jc-m 1", "--jc-T-ref is required with --jc-m > 0"},
        {" --model lps --jc-B 1e8", "--jc-B needs --plasticity johnson-cook"},
        {" --model lps --nsync-mh 5", "--nsync-mh needs a dissipation"},
        {" --model lps" + jc + " --nsync-mh -1", "--nsync-mh must be >= 0"},
        {" --model lps --viscoelastic sls", "--sls-tau is required"},
        {" --model lps --viscoelastic sls --sls-tau -1", "--sls-tau"},
        {" --model correspondence --viscoelastic sls --sls-tau 1e-6", "needs --stress-law flanagan-taylor"},
        {" --model pals --viscoelastic sls --sls-tau 1e-6", "--viscoelastic applies to --model lps, lps-scf or correspondence"},
        {" --model lps" + jc + " --surface-correction energy", "--surface-correction applies to the elastic models"},
        {" --model pals" + jc + " --alpha 1e-5 --T-ref 300 --thermal-strain bond-mean", "bond-mean"},
    };
    for (const auto& [args, message] : cases) {
        const Result r = pd_run("dis_bad", cube + args);
        EXPECT_EQ(r.status, 2) << args << "\n" << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << args << "\n" << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    }
    const Result flat = pd_run("dis_bad_2d", "--input " + stretched_cube(300) + scene + " --dim 2" + jc +
                                                " --model lps --steps 2");
    EXPECT_EQ(flat.status, 2);
    EXPECT_NE(flat.err.find("--plasticity needs --dim 3"), std::string::npos) << flat.err;
}
