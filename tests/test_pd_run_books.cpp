// tests/test_pd_run_books.cpp -- the energy books of build/bin/pd_run's energy.csv (pd::Energies,
// time/verlet.hpp) on the scene a new user tries first: a cloud with every point jittered by up to 30 %
// of the spacing and random initial velocities, free, at pd_run's default step. Reference: conservation
// of energy -- total_J (kinetic + strain + hourglass work + dissipated + released - external work)
// stays at its step-0 value up to velocity Verlet's O(dt^2) error, so balance_error_J shrinks about 4x
// when dt halves. Before the books, correspondence with --hourglass 0.02 lost 18 % of its total to the
// hourglass work that no column held.
#include "pd/io/csv.hpp"

#include <gtest/gtest.h>

#include "pd_run_harness.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

using namespace pd_test;

namespace {
// An n^3 cloud of spacing dx, each point moved by up to 30 % of dx, with random velocities up to 1 m/s.
std::string jittered_cloud(int n, double dx)
{
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> jitter(-0.3 * dx, 0.3 * dx), speed(-1, 1);
    std::string csv = "x,y,z,volume,vx,vy,vz\n";
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                csv += num(i * dx + jitter(gen)) + "," + num(j * dx + jitter(gen)) + "," + num(k * dx + jitter(gen)) + "," + num(dx * dx * dx);
                for (int d = 0; d < 3; ++d) csv += "," + num(speed(gen));
                csv += "\n";
            }
    return write_file("books_cloud.csv", csv).string();
}

struct Column {
    double worst = 0, last = 0;  // largest |value| and last value of a column [J]
};
Column column(const pd::io::CsvTable& e, const std::string& name)
{
    Column c;
    const std::size_t col = e.column(name);
    for (std::size_t q = 0; q < e.rows.size(); ++q) c.worst = std::max(c.worst, std::abs(e.number(q, col)));
    c.last = e.number(e.rows.size() - 1, col);
    return c;
}
}  // namespace

TEST(PdRunBooks, CorrespondenceWithHourglassClosesAtSecondOrder)
{
    const std::string cloud = jittered_cloud(6, 1e-3);
    const std::string args = "--input " + cloud + steel + " --model correspondence --hourglass 0.02 --delta 3e-3 --energy-every 10";
    const Result coarse = pd_run("books_dt", args + " --steps 1000");
    ASSERT_EQ(coarse.status, 0) << coarse.err;
    const auto a = pd::io::read_csv(coarse.dir / "energy.csv");
    const double dt = a.number(1, 1) / 10;  // pd_run's default step [s]
    const Result fine = pd_run("books_dt2", args + " --steps 2000 --energy-every 20 --dt " + num(dt / 2));
    ASSERT_EQ(fine.status, 0) << fine.err;
    const auto b = pd::io::read_csv(fine.dir / "energy.csv");
    ASSERT_EQ(a.rows.size(), b.rows.size());
    const double total0 = a.number(0, a.column("total_J"));
    const Column hg = column(a, "hourglass_work_J"), ea = column(a, "balance_error_J"), eb = column(b, "balance_error_J");
    EXPECT_GT(hg.last, 0.05 * total0);             // the hourglass control takes energy out of the motion ...
    EXPECT_LT(ea.worst, 0.2 * hg.last);            // ... and the books hold it
    EXPECT_GT(ea.worst / eb.worst, 3.5);           // second order (measured: see the report pd_run.md)
    EXPECT_LT(ea.worst / eb.worst, 4.5);
    EXPECT_EQ(column(a, "dissipated_J").worst, 0.0);
    EXPECT_EQ(column(a, "damage_released_J").worst, 0.0);
}
