// tests/test_pd_run.cpp -- build/bin/pd_run (users' point clouds) and its reader pd::io::read_point_cloud.
// References: rigid translation u = v t with zero strain energy (exact for every model); a two-node
// PMB bond in 1D/2D/3D whose first Verlet step is written out by hand from the closed-form
// micromoduli; fixed points; exit status 3 of an unstable run. Output files and bad inputs:
// test_pd_run_contracts.cpp.
#include "pd/io/csv.hpp"
#include "pd/io/point_cloud.hpp"

#include <gtest/gtest.h>

#include "pd_run_harness.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>

namespace fs = std::filesystem;
using pd::io::read_csv;

using namespace pd_test;  // the harness: pd_run, lattice_csv, write_file, steel, ...

// Reader: all columns, comments, CRLF, blanks; absent columns default; fields land in file order.
TEST(PointCloud, ReadsColumnsInAnyOrder)
{
    const auto p = write_file("good.csv", "# a comment\r\nvolume, z,y,x,fixed,vx,block\r\n2e-9,0,0,1e-3,1,0,7\r\n\r\n"
                                          "3e-9,0,0,2e-3,0,5,7\r\n");
    const auto pc = pd::io::read_point_cloud(p, 1);
    ASSERT_EQ(pc.size(), 2u);
    EXPECT_EQ(pc.x[0][1], 2e-3);
    EXPECT_EQ(pc.volume[0], 2e-9);
    EXPECT_EQ(pc.v[0][1], 5.0);
    EXPECT_EQ(pc.u[0][1], 0.0);  // no ux column
    EXPECT_EQ(pc.fixed[0], 1);
    EXPECT_EQ(pc.line[1], 5);    // 1-based, counting the comment and the blank line
    EXPECT_EQ(pc.blocks(), 1);
    EXPECT_EQ(pc.fixed_count(), 1);
}

// Reader errors: one line naming the file, the line and (where there is one) the column.
TEST(PointCloud, ErrorsNameFileLineAndColumn)
{
    struct Case { const char* text; int dim; const char* expect; };
    const Case cases[] = {
        {"x,y,volume\n0,0,1\n", 3, "bad.csv:1: column 'z'"},
        {"x,y,z,volume\n0,0,0,1\nabc,0,0,1\n", 3, "bad.csv:3: column 'x': 'abc' is not a number"},
        {"x,y,z,volume\n0,0,0,nan\n", 3, "bad.csv:2: column 'volume'"},
        {"x,y,z,volume\n0,0,0,1\n1,0,0,0\n", 3, "bad.csv:3: column 'volume': must be positive"},
        {"x,y,z,volume\n0,0,0,1\n1,0,0,1\n0,0,0,1\n", 3, "bad.csv:4: duplicate point (0, 0, 0) already on line 2"},
        {"x,y,z,volume\n", 3, "bad.csv:1: no points"},
        {"x,y,z,volume\n0,0,0\n", 3, "bad.csv:2: expected 4 fields"},
        {"x,y,z,volume,vX\n0,0,0,1,1\n", 3, "bad.csv:1: column 'vX': unknown column"},
        {"x,y,z,volume,fixed\n0,0,0,1,2\n", 3, "bad.csv:2: column 'fixed'"},
        {"x,y,z,volume,block\n0,0,0,1,1.5\n", 3, "bad.csv:2: column 'block'"},
        {"x,y,z,volume\n0,0,0,1\n1,0,0.5,1\n", 2, "bad.csv:3: column 'z'"},
        {"x,y,z,volume,vy\n0,0,0,1,0\n1,0,0,1,3\n", 1, "bad.csv:3: column 'vy': must be 0 in a 1D run"},
        {"x,y,z,volume,fixed,vx\n0,0,0,1,1,2\n", 3, "bad.csv:2: column 'vx': a fixed point"},
    };
    for (const auto& c : cases) {
        const auto p = write_file("bad.csv", c.text);
        try {
            pd::io::read_point_cloud(p, c.dim);
            ADD_FAILURE() << "accepted: " << c.text;
        } catch (const pd::io::PointCloudError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(c.expect), std::string::npos) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
    EXPECT_THROW(pd::io::read_point_cloud(base() / "absent.csv", 3), pd::io::PointCloudError);
    EXPECT_THROW(pd::io::read_point_cloud(base(), 3), pd::io::PointCloudError);  // a folder
    EXPECT_THROW(pd::io::read_point_cloud(write_file("empty.csv", ""), 3), pd::io::PointCloudError);
}

// Rigid translation of a 4^3 lattice, m = 3, v = (1, -2, 0.5) m/s: every bond keeps its length,
// so u = v t and the strain energy stays zero up to round-off. Tolerances: the stretch of a
// translated bond is round-off, |s| <~ 1e-14 over 20 steps (coordinates ~ 4 dx), so the strain
// energy is below 9/2 K s^2 V_total (PMB; LPS is of the same order); u and v drift by the
// resulting force times t^2, far below 1e-10 relative.
TEST(PdRun, RigidTranslationIsExact)
{
    const int n = 4;
    const double dx = 1e-3, vel[3] = {1.0, -2.0, 0.5};
    const auto p = write_file("rigid.csv", lattice_csv(n, dx, ",vx,vy,vz", [&](int, int, int) {
                                  return "," + num(vel[0]) + "," + num(vel[1]) + "," + num(vel[2]);
                              }));
    const double K = 200e9 / (3 * (1 - 2 * 0.25)), s_roundoff = 1e-14;
    const double strain_bound = 4.5 * K * s_roundoff * s_roundoff * n * n * n * dx * dx * dx;
    for (const std::string model : {"pmb", "lps", "scf", "pals", "correspondence"}) {
        const Result r = pd_run("rigid_" + model, "--input " + p.string() + steel + " --model " + model +
                                                      " --delta 3e-3 --steps 20 --energy-every 5 --hourglass 0.02");
        ASSERT_EQ(r.status, 0) << r.err;
        const auto energy = read_csv(r.dir / "energy.csv");
        ASSERT_EQ(energy.rows.size(), 5u);  // steps 0, 5, 10, 15, 20
        for (std::size_t k = 0; k < energy.rows.size(); ++k) EXPECT_LE(std::abs(energy.number(k, 3)), strain_bound);
        const double t = energy.number(4, 1);
        const auto st = read_csv(r.dir / "state_step0020.csv");  // default --output-steps: the last step
        ASSERT_EQ(st.rows.size(), static_cast<std::size_t>(n * n * n));
        for (std::size_t i = 0; i < st.rows.size(); ++i)
            for (int d = 0; d < 3; ++d) {
                EXPECT_NEAR(st.number(i, 4 + d), vel[d] * t, 1e-10 * std::abs(vel[d] * t)) << model << " node " << i;
                EXPECT_NEAR(st.number(i, 7 + d), vel[d], 1e-10 * std::abs(vel[d])) << model << " node " << i;
            }
    }
}

// PMB with the energy surface correction (per-bond factors G_ij scale c): a rigid initial
// displacement u0 = (1, -2, 0.5) x 1e-4 m at rest keeps every bond length, so no force: u stays u0
// and v stays 0. Bound from the round-off stretch |s| <= 1e-14 (as above): |a| <= G_max c |s| sum V_j
// / rho with sum V_j <= 123 dx^3 (the family of delta = 3 dx) and G_max <= 8 (a corner node holds
// >= 1/8 of the full family), so |v| <= |a| t and |u - u0| <= |a| t^2 / 2.
TEST(PdRun, SurfaceCorrectedPmbKeepsARigidDisplacement)
{
    const int n = 4;
    const double dx = 1e-3, delta = 3e-3, u0[3] = {1e-4, -2e-4, 0.5e-4};
    const auto p = write_file("rigid_sc.csv", lattice_csv(n, dx, ",ux,uy,uz", [&](int, int, int) {
                                  return "," + num(u0[0]) + "," + num(u0[1]) + "," + num(u0[2]);
                              }));
    const Result r = pd_run("rigid_sc", "--input " + p.string() + steel + " --model pmb --surface-correction energy --dx " +
                                            num(dx) + " --delta " + num(delta) + " --steps 20");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(slurp(r.dir / "params.csv").find("surface-correction,energy"), std::string::npos);
    const double K = 200e9 / (3 * (1 - 2 * 0.25)), c = 18 * K / (std::numbers::pi * std::pow(delta, 4));
    const double a_bound = 8 * c * 1e-14 * 123 * dx * dx * dx / 7800;  // [m/s^2]
    const auto energy = read_csv(r.dir / "energy.csv");  // steps 0, 10, 20
    ASSERT_EQ(energy.rows.size(), 3u);
    const double t = energy.number(2, 1);  // [s]
    const double strain_bound = 8 * 4.5 * K * 1e-28 * n * n * n * dx * dx * dx;  // G_max 9/2 K s^2 V_total [J]
    for (std::size_t k = 0; k < energy.rows.size(); ++k) EXPECT_LE(std::abs(energy.number(k, 3)), strain_bound);
    const auto st = read_csv(r.dir / "state_step0020.csv");
    ASSERT_EQ(st.rows.size(), static_cast<std::size_t>(n * n * n));
    for (std::size_t i = 0; i < st.rows.size(); ++i)
        for (int d = 0; d < 3; ++d) {
            EXPECT_NEAR(st.number(i, 4 + d), u0[d], a_bound * t * t / 2) << "node " << i;
            EXPECT_NEAR(st.number(i, 7 + d), 0.0, a_bound * t) << "node " << i;
        }
}

// Two nodes at x = 0 and x = L = 1 m, volumes V, bond stretched by s = ux1 / L = 0.01, rho = 1000,
// delta = 1.5 m, omega = 1, dt = 1e-3 s. PMB micromoduli (Silling & Askari 2005, energy matched):
//   3D c = 18 K / (pi delta^4),  K = E / (3 (1 - 2 nu))          (V = 1 m^3)
//   2D c = 12 kappa / (pi delta^3 t), kappa = E / (2 (1 - nu))  (plane stress, t = 0.1 m, V = 0.1 m^3)
//   1D c = 2 E / (A delta^2)                                     (A = 1e-4 m^2, V = 1e-4 m^3)
// with E = 1 MPa, nu = 0.25. Pair force density c s V on node 0 (+x), opposite on node 1, so
//   a0 = c s V / rho;  velocity Verlet: u0(dt) = dt^2/2 a0, u1(dt) = s L - dt^2/2 a0,
//   s1 = s - dt^2 a0 / L,  a1 = c s1 V / rho,  v0(dt) = dt/2 (a0 + a1) = -v1(dt).
// 3D: c = 18 * 666666.67 / (pi 5.0625) = 7.5451e5, a0 = 7.5451 m/s^2, u0 = 3.7726e-6 m.
// Tolerance 1e-10 relative: the library's micromodulus uses the GSL quadrature of M1 (rel. 1e-12).
TEST(PdRun, TwoNodePmbFirstStepMatchesHandValues)
{
    const double pi = std::numbers::pi, E = 1e6, nu = 0.25, rho = 1000, delta = 1.5, L = 1, s = 0.01, dt = 1e-3;
    struct Case { int dim; double V, c; std::string options, yz; };
    const Case cases[] = {
        {3, 1.0, 18 * (E / (3 * (1 - 2 * nu))) / (pi * std::pow(delta, 4)), " --nu 0.25", "0,0"},
        {2, 0.1, 12 * (E / (2 * (1 - nu))) / (pi * std::pow(delta, 3) * 0.1), " --nu 0.25 --thickness 0.1", "0,0.5"},
        {1, 1e-4, 2 * E / (1e-4 * delta * delta), " --area 1e-4", "0.25,0.5"},
    };
    for (const auto& c : cases) {
        const std::string d = std::to_string(c.dim);
        const auto p = write_file("pair" + d + ".csv", "x,y,z,volume,ux\n0," + c.yz + "," + num(c.V) + ",0\n1," +
                                                           c.yz + "," + num(c.V) + "," + num(s * L) + "\n");
        const Result r = pd_run("pair" + d, "--input " + p.string() + " --dim " + d + " --E 1e6" + c.options +
                                                " --rho 1000 --delta 1.5 --dt 1e-3 --steps 1 --output-steps 0,1");
        ASSERT_EQ(r.status, 0) << r.err;
        const double a0 = c.c * s * c.V / rho, s1 = s - dt * dt * a0 / L, a1 = c.c * s1 * c.V / rho;
        const double u0 = dt * dt / 2 * a0, v0 = dt / 2 * (a0 + a1);
        const auto st = read_csv(r.dir / "state_step0001.csv");
        ASSERT_EQ(st.rows.size(), 2u);
        EXPECT_NEAR(st.number(0, 4), u0, 1e-10 * u0) << c.dim << "D";
        EXPECT_NEAR(st.number(1, 4), s * L - u0, 1e-10 * u0) << c.dim << "D";
        EXPECT_NEAR(st.number(0, 7), v0, 1e-10 * v0) << c.dim << "D";
        EXPECT_NEAR(st.number(1, 7), -v0, 1e-10 * v0) << c.dim << "D";
        EXPECT_EQ(st.rows[0].fields[2] + "," + st.rows[0].fields[3], c.yz);  // beyond dim: as read
        for (int k : {5, 6, 8, 9}) EXPECT_EQ(st.rows[1].fields[k], "0");
    }
}

// Fixed points are held at their initial displacement with zero velocity; the free ones move.
TEST(PdRun, FixedPointsHoldTheirInitialDisplacement)
{
    const double dx = 1e-3;
    const auto p = write_file("fixed.csv", lattice_csv(4, dx, ",ux,fixed", [&](int i, int, int) {
                                  return "," + num(1e-3 * (i + 0.5) * dx) + "," + (i == 0 ? "1" : "0");
                              }));
    const Result r = pd_run("fixed", "--input " + p.string() + steel + " --model lps --delta 3e-3 --steps 5");
    ASSERT_EQ(r.status, 0) << r.err;
    const auto st = read_csv(r.dir / "state_step0005.csv");
    for (std::size_t i = 0; i < st.rows.size(); ++i) {
        const bool fixed = i % 4 == 0, x_face = i % 4 == 3;
        if (fixed) {
            EXPECT_EQ(st.number(i, 4), 1e-3 * 0.5 * dx);
            EXPECT_EQ(st.number(i, 7), 0.0);
        }
        if (x_face) {
            EXPECT_LT(st.number(i, 7), 0.0);  // the released stretch pulls the free face back
        }
    }
}

// dt = 20 x the critical step blows up: exit 3, one line on stderr, the step-0 state survives.
TEST(PdRun, UnstableRunExitsThreeAndKeepsEarlierFiles)
{
    const auto p = write_file("unstable.csv", lattice_csv(4, 1e-3, ",ux", [](int i, int, int) {
                                  return "," + num(1e-6 * i);
                              }));
    const Result r = pd_run("unstable", "--input " + p.string() + steel +
                                            " --delta 3e-3 --dt 2e-6 --steps 500 --output-steps 0,400");
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("unstable at step"), std::string::npos) << r.err;
    EXPECT_EQ(read_csv(r.dir / "state_step0000.csv").rows.size(), 64u);
    EXPECT_FALSE(fs::exists(r.dir / "state_step0400.csv"));
    EXPECT_GE(read_csv(r.dir / "energy.csv").rows.size(), 1u);
}
