// tests/test_pd_run_damage.cpp -- critical-stretch bond breaking in build/bin/pd_run (--s0) and the
// point damage phi it writes (state CSV column `damage`, VTU point array `damage`).
// References: hand counts of the broken bonds of a 1D chain with a displacement jump (phi_i = broken
// share of the family, spec/002 eq. 2.17, equal volumes); the contracts of reports/pd_run.md.
#include "pd/io/csv.hpp"

#include <gtest/gtest.h>

#include "pd_run_harness.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using pd::io::read_csv;

namespace {

using pd_test::num;
using pd_test::pd_run;
using pd_test::Result;
using pd_test::slurp;
using pd_test::steel;
using pd_test::write_file;

constexpr int damage_col = 10;  // node_id,x,y,z,ux,uy,uz,vx,vy,vz,damage

// 1D chain of 20 nodes, dx = 1 mm, A = 1e-6 m^2 (V = 1e-9 m^3); nodes 10..19 start displaced by
// d = 1e-6 m, nodes 0..9 at rest: a bond across the cut (between nodes 9 and 10) of length n dx
// starts with stretch d / (n dx) = 1e-3, 5e-4, 3.33e-4 (n = 1, 2, 3); every other bond has s = 0.
std::string jump_chain(const std::string& extra_header = "", const std::string& extra = "")
{
    std::string s = "x,y,z,volume,ux" + extra_header + "\n";
    for (int i = 0; i < 20; ++i) s += num((i + 0.5) * 1e-3) + ",0,0,1e-9," + (i >= 10 ? "1e-6" : "0") + extra + "\n";
    return s;
}

}  // namespace

// s0 = 4e-4 breaks the crossing bonds with n = 1, 2 in start() (before step 0 is written) and keeps
// n = 3 (3.33e-4 < s0). Families of 6 (m = 3, delta = 3 dx) at nodes 3..16, so by hand:
//   node 9: bonds to 10 (n = 1) and 11 (n = 2) broken -> phi = 2/6;  node 8: bond to 10 -> 1/6;
//   node 10: to 9 and 8 -> 2/6;  node 11: to 9 -> 1/6;  every other node 0.
// 3 unordered = 6 ordered bonds broken. Once broken, always broken: the last step has the same phi
// (the unbroken n = 3 bonds carry the pre-stretch and the chain vibrates, but no bond reaches s0:
// the largest stretch stays d / (3 dx) plus the small dynamic part, checked by the unchanged count).
// Tolerance 1e-15: phi = 1 - kept / all with equal volumes is a ratio of small integers.
TEST(PdRunDamage, DisplacementJumpBreaksTheHandCountedBonds)
{
    const auto p = write_file("jump.csv", jump_chain());
    const Result r = pd_run("jump", "--input " + p.string() + " --dim 1 --area 1e-6" + steel +
                                        " --delta 3e-3 --s0 4e-4 --steps 20 --output-steps 0,20 --vtu-every 20");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("broken bonds 6 of"), std::string::npos) << r.out;
    for (const char* f : {"state_step0000.csv", "state_step0020.csv"}) {
        const auto st = read_csv(r.dir / f);
        ASSERT_EQ(st.header.size(), 11u);
        EXPECT_EQ(st.header[damage_col], "damage");
        ASSERT_EQ(st.rows.size(), 20u);
        for (int i = 0; i < 20; ++i) {
            const double phi = i == 9 || i == 10 ? 2.0 / 6 : i == 8 || i == 11 ? 1.0 / 6 : 0.0;
            EXPECT_NEAR(st.number(i, damage_col), phi, 1e-15) << f << " node " << i;
        }
    }
    const std::string vtu = slurp(r.dir / "state_step0020.vtu");
    EXPECT_NE(vtu.find("Name=\"damage\""), std::string::npos);
    // The same cloud with s0 above every initial stretch (1e-3): nothing breaks at the start.
    const Result intact = pd_run("jump_intact", "--input " + p.string() + " --dim 1 --area 1e-6" + steel +
                                                    " --delta 3e-3 --s0 2e-3 --steps 0");
    ASSERT_EQ(intact.status, 0) << intact.err;
    const auto st0 = read_csv(intact.dir / "state_step0000.csv");
    for (std::size_t i = 0; i < st0.rows.size(); ++i) EXPECT_EQ(st0.number(i, damage_col), 0.0) << "node " << i;
}

// No-fail points (column no_fail = 1 on nodes 9 and 10), same jump and s0 = 4e-4: the bonds beyond s0
// are 9-10 (n = 1), 9-11 and 8-10 (n = 2); each touches node 9 or 10, so none breaks and phi = 0.
TEST(PdRunDamage, NoFailPointsKeepTheirBonds)
{
    std::string s = "x,y,z,volume,ux,no_fail\n";
    for (int i = 0; i < 20; ++i)
        s += num((i + 0.5) * 1e-3) + ",0,0,1e-9," + (i >= 10 ? "1e-6" : "0") + (i == 9 || i == 10 ? ",1" : ",0") + "\n";
    const auto p = write_file("jump_nofail.csv", s);
    const Result r = pd_run("jump_nofail", "--input " + p.string() + " --dim 1 --area 1e-6" + steel +
                                               " --delta 3e-3 --s0 4e-4 --steps 0");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("broken bonds 0 of"), std::string::npos) << r.out;
    const auto st = read_csv(r.dir / "state_step0000.csv");
    for (std::size_t i = 0; i < st.rows.size(); ++i) EXPECT_EQ(st.number(i, damage_col), 0.0) << "node " << i;
}

// A 3D block 8 x 4 x 4 (dx = 1 mm, m = 3) pulled apart: the halves ix < 4 and ix >= 4 start at -/+ 20 m/s.
// Each half moves rigidly; only the bonds across the mid-plane stretch, at 2 v / |xi| >= 1.3e4 /s, and
// pass s0 = 1e-3 within ~2e-7 s (a few steps of ~1e-7 s); the forces they carry until then (stretch
// below s0, spread over the halves) strain no other bond up to s0. So the block is cut: at steps 20 and 40 every crossing bond and no other is broken, and phi_i = (crossing
// bonds of i) / (bonds of i), counted below by an independent walk over the lattice (|n|^2 <= 9,
// equal volumes). Step 0 has no stretch and no damage. Tolerance 1e-15: ratios of small integers.
TEST(PdRunDamage, PulledBlockIsCutAlongTheMidPlane)
{
    const double dx = 1e-3, v = 20;
    const int nx = 8, ny = 4, nz = 4;
    std::string s = "x,y,z,volume,vx\n";
    std::vector<double> phi_ref;
    long crossing_total = 0, bonds_total = 0;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                s += num((i + 0.5) * dx) + "," + num((j + 0.5) * dx) + "," + num((k + 0.5) * dx) + ",1e-9," +
                     num(i < 4 ? -v : v) + "\n";
                int all = 0, crossing = 0;
                for (int c = -3; c <= 3; ++c)
                    for (int b = -3; b <= 3; ++b)
                        for (int a = -3; a <= 3; ++a) {
                            const int r2 = a * a + b * b + c * c;
                            if (r2 == 0 || r2 > 9 || i + a < 0 || i + a >= nx || j + b < 0 || j + b >= ny ||
                                k + c < 0 || k + c >= nz)
                                continue;
                            ++all;
                            crossing += (i < 4) != (i + a < 4);
                        }
                phi_ref.push_back(static_cast<double>(crossing) / all);
                crossing_total += crossing;
                bonds_total += all;
            }
    const auto p = write_file("pulled.csv", s);
    for (const std::string model : {"pmb", "lps"}) {
        const Result r = pd_run("pulled_" + model, "--input " + p.string() + steel + " --model " + model +
                                                       " --delta 3e-3 --s0 1e-3 --steps 40 --output-steps 0,20,40 --vtu-every 40");
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_NE(r.out.find("broken bonds " + std::to_string(crossing_total) + " of " + std::to_string(bonds_total)),
                  std::string::npos) << r.out;
        const auto st0 = read_csv(r.dir / "state_step0000.csv");
        for (std::size_t i = 0; i < st0.rows.size(); ++i) EXPECT_EQ(st0.number(i, damage_col), 0.0) << model;
        for (const char* f : {"state_step0020.csv", "state_step0040.csv"}) {
            const auto st = read_csv(r.dir / f);
            ASSERT_EQ(st.rows.size(), phi_ref.size());
            for (std::size_t i = 0; i < st.rows.size(); ++i)
                EXPECT_NEAR(st.number(i, damage_col), phi_ref[i], 1e-15) << model << " " << f << " node " << i;
        }
        EXPECT_NE(slurp(r.dir / "state_step0040.vtu").find("Name=\"damage\""), std::string::npos);
    }
}

// --s0 errors: exit 2 and one line naming the option (or the column).
TEST(PdRunDamage, BadInputsExitTwoWithOneLine)
{
    const std::string chain = write_file("jump_ok.csv", jump_chain()).string();
    const std::string flags = write_file("jump_flags.csv", jump_chain(",no_fail", ",0")).string();
    const std::string bad_flag = write_file("jump_badflag.csv", jump_chain(",no_fail", ",2")).string();
    const std::string in = "--input " + chain + " --dim 1" + steel + " --delta 3e-3 --steps 2";
    struct Case { std::string args, expect; };
    const std::vector<Case> cases = {
        {in + " --s0 0", "option --s0 must be > 0, got 0"},
        {in + " --s0 -1e-3", "option --s0 must be > 0"},
        {in + " --s0 abc", "option --s0 expects a number, got 'abc'"},
        {in + " --s0 nan", "option --s0"},
        {"--input " + flags + " --dim 1" + steel + " --delta 3e-3", "column 'no_fail' needs --s0"},
        {"--input " + bad_flag + " --dim 1" + steel + " --delta 3e-3 --s0 1e-3", "column 'no_fail': must be 0 or 1"},
    };
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const Result r = pd_run("bad_s0_" + std::to_string(k), cases[k].args);
        EXPECT_EQ(r.status, 2) << cases[k].args;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_NE(r.err.find(cases[k].expect), std::string::npos) << cases[k].args << "\n" << r.err;
    }
}
