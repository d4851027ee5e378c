// tests/test_pd_run_heat.cpp -- heat conduction in build/bin/pd_run (--heat, columns T0 and T_fixed).
// References: two-node first explicit-Euler steps written out by hand from the closed-form Agwai
// micro-conductivities (and, for 1D correspondence, from the exact 1D gradient); held temperatures
// stay held; an insulated cloud conserves sum rho cv V T (the bond heat flows are antisymmetric);
// the two-node difference mode of explicit Euler grows by |1 - 2 dt/dt_crit| per step; the input
// and exit-status contracts of reports/pd_run.md.
#include "pd/io/csv.hpp"
#include "pd/io/point_cloud.hpp"

#include <gtest/gtest.h>

#include "pd_run_harness.hpp"

#include <algorithm>
#include <functional>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using pd::io::read_csv;
using pd_test::base;
using pd_test::num;
using pd_test::pd_run;
using pd_test::Result;
using pd_test::slurp;
using pd_test::write_file;

namespace {

constexpr double pi = std::numbers::pi;
const std::string heat_only = " --mechanics off --rho 1000 --cv 500 --k 50";  // rho cv = 5e5 J/(m^3 K)

// n^3 lattice of spacing 1 mm, volume (1 + (i % 3) / 2) mm^3 (uneven on purpose), T0 = 10 (i + 2j + 3k)
// and a T_fixed column from `held(i, j, k)` ("" = free).
std::string lattice(int n, const std::function<std::string(int, int, int)>& held)
{
    std::string s = "x,y,z,volume,T0,T_fixed\n";
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                s += num(i * 1e-3) + "," + num(j * 1e-3) + "," + num(k * 1e-3) + "," + num((1 + (i % 3) / 2.0) * 1e-9) +
                     "," + num(10.0 * (i + 2 * j + 3 * k)) + "," + held(i, j, k) + "\n";
    return s;
}

// sum V T over a state file (column T is 4, volumes from the lattice above).
double heat_content(const pd::io::CsvTable& st, int n)
{
    double H = 0;
    for (std::size_t r = 0; r < st.rows.size(); ++r) H += (1 + (int(r) % n % 3) / 2.0) * 1e-9 * st.number(r, 4);
    return H;
}

}  // namespace

// Reader: T0 numbers, T_fixed numbers or empty (free = NaN); a malformed value names file, line, column.
TEST(PointCloudHeat, ReadsTemperatureColumns)
{
    const auto p = write_file("t.csv", "x,y,z,volume,T_fixed,T0\n0,0,0,1,,20\n1,0,0,1,300, 21.5\n");
    const auto pc = pd::io::read_point_cloud(p, 3);
    EXPECT_EQ(pc.T0[1], 21.5);
    EXPECT_TRUE(std::isnan(pc.T_fixed[0]));
    EXPECT_EQ(pc.T_fixed[1], 300.0);
    const auto q = pd::io::read_point_cloud(write_file("u.csv", "x,y,z,volume\n0,0,0,1\n"), 3);
    EXPECT_TRUE(std::isnan(q.T0[0]) && std::isnan(q.T_fixed[0]));  // absent columns
}

// Two nodes at x = 0 and x = L = 1 m, T0 = 100 and 0, rho cv = 5e5 J/(m^3 K), k = 50 W/(m K),
// delta = 1.5 m, dt = 1000 s. Agwai micro-conductivity kappa_1 = 6k/(pi delta^4) (3D),
// 6k/(pi t delta^3) (2D, t = 0.1 m, V = 0.1 m^3), 2k/(A delta^2) (1D, A = 1e-4 m^2, V = 1e-4 m^3);
// Q_0 = kappa_1 V (T_1 - T_0)/L and T_0 += dt Q_0/(rho cv):
//   3D kappa_1 = 300/(pi 5.0625) = 18.8628, Q_0 = -1886.28 W/m^3, T_0(dt) = 100 - 3.77256 = 96.2274.
// 1D correspondence (K = V L^2, g = (T_1 - T_0)/L at both nodes, a = k g/K, no hourglass term):
//   Q_0 = V (a_0 + a_1) L = 2 k (T_1 - T_0)/L^2 = -1e4 W/m^3, T_0(dt) = 100 - 20 = 80.
// Tolerance 1e-10 relative: kappa_1 goes through the GSL quadrature of M_1 (rel. 1e-12).
TEST(PdRunHeat, TwoNodeFirstStepMatchesHandValues)
{
    const double k = 50, rho_cv = 5e5, dt = 1000, delta = 1.5;
    struct Case { std::string dim, heat, options; double V, Q0; };
    const Case cases[] = {
        {"3", "agwai", "", 1.0, -100 * 6 * k / (pi * std::pow(delta, 4))},
        {"2", "agwai", " --thickness 0.1", 0.1, -100 * 0.1 * 6 * k / (pi * 0.1 * std::pow(delta, 3))},
        {"1", "agwai", " --area 1e-4", 1e-4, -100 * 1e-4 * 2 * k / (1e-4 * delta * delta)},
        {"1", "correspondence", " --area 1e-4", 1e-4, 2 * k * -100},
    };
    for (const auto& c : cases) {
        const std::string tag = "pair" + c.dim + c.heat;
        const auto p = write_file(tag + ".csv", "x,y,z,volume,T0\n0,0,0," + num(c.V) + ",100\n1,0,0," + num(c.V) + ",0\n");
        const Result r = pd_run(tag, "--input " + p.string() + " --dim " + c.dim + c.options + heat_only + " --heat " +
                                         c.heat + " --delta 1.5 --dt-thermal 1000 --thermal-steps 1 --output-steps 0,1");
        ASSERT_EQ(r.status, 0) << r.err;
        const auto s0 = read_csv(r.dir / "state_step0000.csv"), s1 = read_csv(r.dir / "state_step0001.csv");
        ASSERT_EQ(s1.header, (std::vector<std::string>{"node_id", "x", "y", "z", "T", "Q_W_m3"}));
        EXPECT_NEAR(s0.number(0, 5), c.Q0, 1e-10 * std::abs(c.Q0)) << tag;
        EXPECT_NEAR(s0.number(1, 5), -c.Q0, 1e-10 * std::abs(c.Q0)) << tag;
        const double dT = dt * c.Q0 / rho_cv;
        EXPECT_NEAR(s1.number(0, 4), 100 + dT, 1e-10 * std::abs(dT)) << tag;
        EXPECT_NEAR(s1.number(1, 4), -dT, 1e-10 * std::abs(dT)) << tag;
    }
}

// The same 3D pair with the other integrators. The difference d = T_1 - T_0 (d_0 = -100) obeys
// d' = -2 r d, r = kappa_1 V/(|xi| rho cv) = 18.8628/5e5 1/s; the mean 50 is kept. Implicit Euler:
// d_1 = d_0/(1 + 2 r dt) (T_0 = 96.4921 at dt = 1000 s); CVODE BDF: the exact d_0 exp(-2 r t) at
// t = 1000 s (T_0 = 96.3662), to 1e-6 relative (rtol = atol = 1e-8 per step over ~100 internal steps).
TEST(PdRunHeat, TwoNodeImplicitAndCvodeMatchClosedForms)
{
    const double r = 6 * 50 / (pi * std::pow(1.5, 4)) / 5e5, dt = 1000;
    const auto p = write_file("pair.csv", "x,y,z,volume,T0\n0,0,0,1,100\n1,0,0,1,0\n");
    struct Case { std::string integrator; double d1, tol; };
    const Case cases[] = {{"implicit", -100 / (1 + 2 * r * dt), 1e-12}, {"cvode", -100 * std::exp(-2 * r * dt), 1e-6}};
    for (const auto& c : cases) {
        const Result res = pd_run("pair_" + c.integrator, "--input " + p.string() + heat_only + " --heat agwai --delta 1.5" +
                                                              " --dt-thermal 1000 --thermal-steps 1 --thermal-integrator " + c.integrator);
        ASSERT_EQ(res.status, 0) << res.err;
        const auto st = read_csv(res.dir / "state_step0001.csv");
        EXPECT_NEAR(st.number(0, 4), 50 - c.d1 / 2, c.tol * 100) << c.integrator;
        EXPECT_NEAR(st.number(1, 4), 50 + c.d1 / 2, c.tol * 100) << c.integrator;
    }
}

// Held temperatures are applied from step 0 and stay exact; with Agwai and a step below the
// critical one the free nodes stay within the range of the initial and held values (maximum principle).
TEST(PdRunHeat, HeldTemperaturesStayHeld)
{
    const int n = 4;
    const auto p = write_file("held.csv", lattice(n, [](int i, int, int) { return i == 0 ? std::string("500") : ""; }));
    for (const std::string integrator : {"explicit", "implicit", "cvode"}) {
        const Result r = pd_run("held_" + integrator, "--input " + p.string() + heat_only + " --heat agwai --delta 2.5e-3" +
                                                          " --thermal-steps 20 --output-steps 0,20 --thermal-integrator " + integrator);
        ASSERT_EQ(r.status, 0) << r.err;
        for (const char* f : {"state_step0000.csv", "state_step0020.csv"}) {
            const auto st = read_csv(r.dir / f);
            for (std::size_t i = 0; i < st.rows.size(); ++i) {
                if (i % n == 0) EXPECT_EQ(st.number(i, 4), 500.0) << integrator << " " << f << " node " << i;
                else EXPECT_GE(st.number(i, 4), 0.0) << integrator << " node " << i;
                EXPECT_LE(st.number(i, 4), 500.0) << integrator << " node " << i;
            }
        }
        EXPECT_GT(read_csv(r.dir / "state_step0020.csv").number(1, 4), 10.0) << integrator;  // heated from x = 0 (T0 = 10)
    }
}

// Insulated cloud (no held node), uneven volumes: sum_i V_i Q_i = 0 because the bond flows are
// antisymmetric (Agwai kappa_1 V_i V_j/|xi|; correspondence h_i - h_j), so sum rho cv V T is kept
// by explicit and implicit Euler up to round-off (1e-12 relative: ~1e3 additions of terms of the
// size of the sum) and by CVODE up to its tolerances (rtol = atol = 1e-8, 1e-7 relative over 30 steps).
TEST(PdRunHeat, InsulatedCloudConservesHeat)
{
    const int n = 4;
    const auto p = write_file("insulated.csv", lattice(n, [](int, int, int) { return ""; }));
    struct Case { std::string heat, integrator; double tol; };
    const Case cases[] = {{"agwai", "explicit", 1e-12}, {"agwai", "implicit", 1e-12}, {"agwai", "cvode", 1e-7},
                          {"correspondence --heat-hourglass 0.02", "explicit", 1e-12}};
    for (const auto& c : cases) {
        const std::string tag = "ins" + std::to_string(&c - cases);
        const Result r = pd_run(tag, "--input " + p.string() + heat_only + " --heat " + c.heat + " --delta 2.5e-3" +
                                         " --thermal-steps 30 --output-steps 0,30 --thermal-integrator " + c.integrator);
        ASSERT_EQ(r.status, 0) << r.err;
        const double H0 = heat_content(read_csv(r.dir / "state_step0000.csv"), n);
        const auto end = read_csv(r.dir / "state_step0030.csv");
        EXPECT_NEAR(heat_content(end, n), H0, c.tol * H0) << c.heat << " " << c.integrator;
        double lo = 1e300, hi = -1e300;
        for (std::size_t i = 0; i < end.rows.size(); ++i) lo = std::min(lo, end.number(i, 4)), hi = std::max(hi, end.number(i, 4));
        EXPECT_LT(hi - lo, 180.0) << c.heat;  // it diffuses: the initial range is 0..180
        const auto log = read_csv(r.dir / "heat.csv");  // heat_J = rho cv sum V T
        EXPECT_NEAR(log.number(0, 2), 5e5 * H0, 1e-12 * 5e5 * H0);
    }
}

// Every invalid heat input exits 2 with ONE stderr line naming the option or the file, line and column.
TEST(PdRunHeat, BadInputsExitTwoWithOneLine)
{
    const std::string good = write_file("ok.csv", "x,y,z,volume,T0\n0,0,0,1e-9,1\n1e-3,0,0,1e-9,2\n").string();
    const std::string plain = write_file("plain.csv", "x,y,z,volume\n0,0,0,1e-9\n1e-3,0,0,1e-9\n").string();
    const std::string moving = write_file("moving.csv", "x,y,z,volume,T0,vx\n0,0,0,1e-9,1,0\n1e-3,0,0,1e-9,2,0\n").string();
    const std::string bad_T0 = write_file("bad_T0.csv", "x,y,z,volume,T0\n0,0,0,1e-9,1\n1e-3,0,0,1e-9,warm\n").string();
    const std::string empty_T0 = write_file("empty_T0.csv", "x,y,z,volume,T0\n0,0,0,1e-9,\n1e-3,0,0,1e-9,2\n").string();
    const std::string bad_Tf = write_file("bad_Tf.csv", "x,y,z,volume,T0,T_fixed\n0,0,0,1e-9,1,\n1e-3,0,0,1e-9,2,inf\n").string();
    const std::string in = "--input " + good + " --delta 2e-3";
    const std::string steel = " --E 200e9 --nu 0.25 --rho 7800 --steps 5";
    struct Case { std::string args, expect; };
    const std::vector<Case> cases = {
        {in + heat_only + " --heat foo", "--heat"},
        {in + heat_only + " --heat agwai --k -1", "--k"},
        {in + " --mechanics off --rho 1000 --cv 500 --heat agwai", "--k is required"},
        {in + heat_only + " --heat agwai --cv 0", "--cv"},
        {in + heat_only + " --heat agwai --dt-thermal 0", "--dt-thermal"},
        {in + heat_only + " --heat agwai --thermal-steps -1", "--thermal-steps"},
        {in + heat_only + " --heat agwai --thermal-integrator rk4", "--thermal-integrator"},
        {in + heat_only + " --heat agwai --heat-hourglass 0.02", "--heat-hourglass"},
        {in + heat_only + " --heat correspondence --heat-hourglass -1", "--heat-hourglass"},
        {in + heat_only + " --heat correspondence --thermal-correction per-node", "--thermal-correction"},
        {in + heat_only + " --heat agwai --T0 20", "--T0 is ambiguous"},
        {in + heat_only + " --heat agwai --E 1e9", "--E applies to the mechanics"},
        {in + heat_only + " --heat agwai --steps 3", "--steps"},
        {in + heat_only + " --heat agwai --thermal-steps 3 --output-steps 4", "step 4 is beyond --thermal-steps 3"},
        {in + heat_only, "--mechanics off needs --heat"},
        {in + steel + " --k 50", "--k needs --heat"},
        {in + steel + " --heat agwai --k 50 --cv 500 --thermal-steps 3", "--thermal-steps applies to --mechanics off"},
        {"--input " + plain + " --delta 2e-3" + heat_only + " --heat agwai", "--T0 is required"},
        {in + steel, "ok.csv: column 'T0' needs --heat"},
        {"--input " + moving + " --delta 2e-3" + heat_only + " --heat agwai", "moving.csv: column 'vx' needs the mechanics"},
        {"--input " + bad_T0 + " --delta 2e-3" + heat_only + " --heat agwai", "bad_T0.csv:3: column 'T0': 'warm' is not a number"},
        {"--input " + empty_T0 + " --delta 2e-3" + heat_only + " --heat agwai", "empty_T0.csv:2: column 'T0'"},
        {"--input " + bad_Tf + " --delta 2e-3" + heat_only + " --heat agwai", "bad_Tf.csv:3: column 'T_fixed': 'inf'"},
    };
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const Result r = pd_run("bad" + std::to_string(k), cases[k].args);
        EXPECT_EQ(r.status, 2) << cases[k].args;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_NE(r.err.find(cases[k].expect), std::string::npos) << cases[k].args << "\n" << r.err;
    }
}

// Two nodes (as in TwoNodeFirstStepMatchesHandValues, 3D, T0 = 100 and 0): the difference
// d = T_1 - T_0 obeys d <- (1 - 2 dt/dt_crit) d with dt_crit = rho cv L/(kappa_1 V) = 26507.2 s.
// dt = 3 dt_crit: factor -5; d = -100, 500, -2500: step 1 T = (-200, 300), step 2 T_0 = 50 + 1250 =
// 1300, outside the guard band [0 - 10 x 100, 100 + 10 x 100]: exit 3 at thermal step 2, node 0,
// earlier files kept.
TEST(PdRunHeat, ExplicitAboveCriticalStepExitsThree)
{
    const double dt_crit = 5e5 * pi * std::pow(1.5, 4) / (6 * 50);
    const auto p = write_file("unstable.csv", "x,y,z,volume,T0\n0,0,0,1,100\n1,0,0,1,0\n");
    const Result r = pd_run("unstable", "--input " + p.string() + heat_only + " --heat agwai --delta 1.5 --dt-thermal " +
                                            num(3 * dt_crit) + " --thermal-steps 10 --output-steps 0,1,5 --energy-every 1");
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("heat run unstable at thermal step 2, node 0"), std::string::npos) << r.err;
    const auto s1 = read_csv(r.dir / "state_step0001.csv");
    EXPECT_NEAR(s1.number(0, 4), -200, 1e-9 * 200);  // 1e-9: dt_crit printed to 17 digits, kappa_1 rel. 1e-12
    EXPECT_NEAR(s1.number(1, 4), 300, 1e-9 * 300);
    EXPECT_FALSE(fs::exists(r.dir / "state_step0005.csv"));
    EXPECT_EQ(read_csv(r.dir / "heat.csv").rows.size(), 2u);  // thermal steps 0 and 1
    EXPECT_NE(r.out.find("warning: --dt-thermal exceeds"), std::string::npos);
}

// With the mechanics on, the heat follows the mechanical clock: dt = 1e-3 s, dt_thermal = 2.5e-3 s,
// 10 steps -> thermal steps floor(n 0.4): 4 in all, the same temperatures as a heat-only run of 4
// thermal steps (no coupling); the state file carries u, v, T and Q, the VTU the arrays T and Q_W_m3.
// E = 1 Pa keeps dt below the mechanical critical step (~0.027 s) of the cloud at rest.
TEST(PdRunHeat, HeatFollowsTheMechanicalClock)
{
    const auto p = write_file("both.csv", lattice(3, [](int i, int, int) { return i == 0 ? std::string("90") : ""; }));
    const std::string heat = " --heat agwai --k 50 --cv 500 --delta 2.5e-3 --dt-thermal 2.5e-3";
    const Result both = pd_run("both", "--input " + p.string() + heat + " --E 1 --nu 0.25 --rho 1000 --dt 1e-3" +
                                           " --steps 10 --energy-every 1 --vtu-every 10");
    ASSERT_EQ(both.status, 0) << both.err;
    const Result alone = pd_run("alone", "--input " + p.string() + heat + " --mechanics off --rho 1000 --thermal-steps 4");
    ASSERT_EQ(alone.status, 0) << alone.err;
    const auto log = read_csv(both.dir / "heat.csv");
    ASSERT_EQ(log.rows.size(), 5u);
    EXPECT_EQ(log.rows[4].fields[0], "4");
    const auto sb = read_csv(both.dir / "state_step0010.csv"), sa = read_csv(alone.dir / "state_step0004.csv");
    ASSERT_EQ(sb.header.size(), 12u);
    EXPECT_EQ(sb.header[10], "T");
    EXPECT_EQ(sb.header[11], "Q_W_m3");
    for (std::size_t i = 0; i < sa.rows.size(); ++i) {
        EXPECT_EQ(sb.rows[i].fields[10], sa.rows[i].fields[4]) << i;
        EXPECT_EQ(sb.rows[i].fields[11], sa.rows[i].fields[5]) << i;
    }
    const std::string vtu = slurp(both.dir / "state_step0010.vtu");
    EXPECT_NE(vtu.find("Name=\"T\""), std::string::npos);
    EXPECT_NE(vtu.find("Name=\"Q_W_m3\""), std::string::npos);
}

// The heat loop is owner-computes with a fixed summation order: 1 and 2 threads give the same
// file, byte for byte (correspondence heat: point pass and bond pass both run in parallel).
TEST(PdRunHeat, ThreadCountDoesNotChangeTemperatures)
{
    const auto p = write_file("threads.csv", lattice(4, [](int i, int, int) { return i == 3 ? std::string("0") : ""; }));
    std::string files[2];
    for (int t : {1, 2}) {
        const Result r = pd_run("threads" + std::to_string(t),
                                "--input " + p.string() + heat_only + " --heat correspondence --heat-hourglass 0.02" +
                                    " --delta 2.5e-3 --thermal-steps 10 --threads " + std::to_string(t));
        ASSERT_EQ(r.status, 0) << r.err;
        files[t - 1] = slurp(r.dir / "state_step0010.csv");
    }
    EXPECT_FALSE(files[0].empty());
    EXPECT_EQ(files[0], files[1]);
}
