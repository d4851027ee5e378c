// pd_run --model lps --surface-correction energy (issue 3: every elastic model of a user's point
// cloud, with the surface correction where the library has one). The correction itself is checked
// in tests/test_surface_correction_lps.cpp; here: the option reaches the model. A 4 x 4 x 4 block
// (every node within delta of a surface) stretched by u_x = eps x and released: the first step's
// velocities must differ from those of the uncorrected run (the factors scale the surface bonds)
// by more than round-off, while both runs share everything else.
#include "pd/io/csv.hpp"

#include <gtest/gtest.h>

#include "pd_run_harness.hpp"

#include <algorithm>
#include <cmath>
#include <string>

using pd::io::read_csv;
using namespace pd_test;  // the harness: pd_run, lattice_csv, write_file, steel, ...

TEST(PdRun, LpsSurfaceCorrectionReachesTheModel)
{
    const int n = 4;
    const double dx = 1e-3, eps = 1e-3;
    const auto p = write_file("lps_sc.csv", lattice_csv(n, dx, ",ux", [&](int i, int, int) { return std::string(",") + num(eps * (i + 0.5) * dx); }));
    const std::string args = "--input " + p.string() + steel + " --model lps --delta 3e-3 --dt 1e-9 --steps 1";
    const Result off = pd_run("lps_sc_off", args);
    const Result on = pd_run("lps_sc_on", args + " --surface-correction energy");
    ASSERT_EQ(off.status, 0) << off.err;
    ASSERT_EQ(on.status, 0) << on.err;
    EXPECT_NE(slurp(on.dir / "params.csv").find("surface-correction,energy"), std::string::npos);
    const auto a = read_csv(off.dir / "state_step0001.csv"), b = read_csv(on.dir / "state_step0001.csv");
    ASSERT_EQ(a.rows.size(), static_cast<std::size_t>(n * n * n));
    ASSERT_EQ(b.rows.size(), a.rows.size());
    double vmax = 0, dmax = 0;  // v_x [m/s] after one step
    for (std::size_t i = 0; i < a.rows.size(); ++i) {
        vmax = std::max(vmax, std::abs(a.number(i, 7)));
        dmax = std::max(dmax, std::abs(b.number(i, 7) - a.number(i, 7)));
    }
    ASSERT_GT(vmax, 0.0);
    EXPECT_GT(dmax, 1e-3 * vmax);  // factors differ from 1 by O(10 %) at a corner, round-off by 1e-16
}
