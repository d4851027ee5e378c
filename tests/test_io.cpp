// tests/test_io.cpp -- pd::io: non-finite headlines of a case's summary.csv, convergence.csv headers
// and the observed convergence rate, VTU/PVD files, timer and progress display (CSV files:
// test_io_csv.cpp; options and their exit-2 contract: test_io_options.cpp).
#include "pd/core/errors.hpp"
#include "pd/io/case.hpp"
#include "pd/io/convergence.hpp"
#include "pd/io/csv.hpp"
#include "pd/core/timer.hpp"
#include "pd/io/refined_grid_vtu.hpp"
#include "pd/io/vtu.hpp"

#include <gtest/gtest.h>

#include "io_fixtures.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace {

using pd_test::first_line;
using pd_test::slurp;
using pd_test::temp_path;

// A measured headline that is nan or inf ends the run (NonFiniteResult: exit status 3 with
// guarded_main) after summary.csv is written; a not_measured row is written as nan and passes.
TEST(IoCase, NonFiniteHeadlineIsAnErrorUnlessNotMeasured)
{
    const std::string out = temp_path("case_nonfinite");
    const char* argv[] = {"case_test", "--out", out.c_str()};
    const double nan = std::nan("");
    for (const double bad : {nan, double(INFINITY)}) {
        pd::io::Case run("case_test", "finish with a non-finite headline", out);
        run.start(3, argv);
        run.summary({{"speed_m_s", 5000, 5100, pd::io::relative_error(5000, 5100), "m/s"}, {"energy_J", bad, nan, nan, "J"}});
        EXPECT_THROW(run.finish("done"), pd::NonFiniteResult);
        const auto t = pd::io::read_csv(out + "/summary.csv");
        ASSERT_EQ(t.rows.size(), 2u);
        EXPECT_EQ(t.rows[1].fields[0], "energy_J");
    }
    pd::io::Case run("case_test", "finish with a quantity not measured", out);
    run.start(3, argv);
    run.summary({{"speed_m_s", 5000, 5100, pd::io::relative_error(5000, 5100), "m/s"}, pd::io::not_measured("nodes_refined", 26644, "-")});
    EXPECT_EQ(run.finish("done"), 0);
    const auto t = pd::io::read_csv(out + "/summary.csv");
    ASSERT_EQ(t.rows.size(), 2u);
    EXPECT_EQ(t.rows[1].fields, (std::vector<std::string>{"nodes_refined", "nan", "26644", "nan", "-"}));
}

TEST(IoConvergence, SecondOrderErrorGivesRateTwo)
{
    // error = C h^2 on an irregular sequence of spacings: every rate is 2 up to rounding
    // (a few ulps in the logarithms, hence 1e-12).
    const double C = 7.3;
    pd::io::ConvergenceTable table;
    for (double dx : {0.1, 0.05, 0.03, 0.0125, 0.001})
        table.add({.dx_m = dx, .delta_m = 3 * dx, .m = 3, .nodes = static_cast<long long>(1 / dx), .bonds = 6,
                   .error = C * dx * dx, .wall_s = 0.01});
    EXPECT_TRUE(std::isnan(table.rate(0)));
    for (std::size_t k = 1; k < table.size(); ++k) EXPECT_NEAR(table.rate(k), 2.0, 1e-12) << k;

    const std::string path = temp_path("convergence/plain.csv");
    table.write_csv(path);
    EXPECT_EQ(first_line(path), "dx_m,delta_m,m,nodes,bonds,error,rate,wall_s");
    const auto t = pd::io::read_csv(path);
    ASSERT_EQ(t.rows.size(), 5u);
    EXPECT_EQ(t.rows[0].fields[6], "nan");
    EXPECT_NEAR(t.number(2, 6), 2.0, 1e-12);
    EXPECT_EQ(t.rows[1].fields[3], "20");  // nodes written as an integer
}

TEST(IoConvergence, LabelsExtrasAndPrint)
{
    pd::io::ConvergenceTable table({"study"}, {"f1_Hz"});
    table.add({.dx_m = 0.1, .delta_m = 0.3, .m = 3, .nodes = 10, .bonds = 60, .error = 1e-2, .wall_s = 0.1,
               .labels = {"delta"}, .extras = {100.0}});
    table.add({.dx_m = 0.05, .delta_m = 0.15, .m = 3, .nodes = 20, .bonds = 120, .error = 2.5e-3, .wall_s = 0.2,
               .labels = {"delta"}, .extras = {101.0}});
    table.add({.dx_m = 0.025, .delta_m = 0.3, .m = 12, .nodes = 40, .bonds = 960, .error = 4e-3, .wall_s = 0.4,
               .labels = {"m"}, .extras = {102.0}});
    EXPECT_NEAR(table.rate(1), 2.0, 1e-12);
    EXPECT_TRUE(std::isnan(table.rate(2)));  // a new study starts: no rate against the other study
    EXPECT_THROW(table.add({.dx_m = 1, .labels = {}}), std::invalid_argument);

    const std::string path = temp_path("convergence/labelled.csv");
    table.write_csv(path);
    EXPECT_EQ(first_line(path), "study,dx_m,delta_m,m,nodes,bonds,error,rate,wall_s,f1_Hz");

    std::ostringstream os;
    table.print(os);
    std::istringstream lines(os.str());
    std::string line;
    std::vector<std::string> all;
    while (std::getline(lines, line)) all.push_back(line);
    ASSERT_EQ(all.size(), 4u);
    EXPECT_NE(all[0].find("dx_m"), std::string::npos);
    for (const auto& l : all) EXPECT_EQ(l.size(), all[0].size()) << l;  // aligned columns
    EXPECT_NE(all[2].find(" 2.00 "), std::string::npos) << all[2];
}

TEST(IoVtu, WellFormedPointsAndArrays)
{
    const std::vector<double> x{0, 1, 2, 3, 4}, y{0, 0, 1, 1, 2}, phi{0, 0.1, 0.2, 0.3, 1};
    const std::vector<double> packed{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};  // D = 3
    const std::string path = temp_path("vtu/state.vtu");
    pd::io::VtuWriter w(path);
    w.points(x, y);
    w.scalar("damage", phi);
    w.vector("displacement_m", x, y);
    w.vector_interleaved("velocity_m_per_s", packed, 3);
    w.time(0.5);
    EXPECT_THROW(w.scalar("short", {1.0, 2.0}), std::invalid_argument);
    EXPECT_THROW(w.scalar("damage", phi), std::invalid_argument);  // duplicate name
    w.write();

    const std::string s = slurp(path);
    EXPECT_EQ(s.rfind("<?xml", 0), 0u);
    EXPECT_NE(s.find("<VTKFile type=\"UnstructuredGrid\""), std::string::npos);
    EXPECT_NE(s.find("NumberOfPoints=\"5\" NumberOfCells=\"5\""), std::string::npos);
    EXPECT_NE(s.find("Name=\"damage\" NumberOfComponents=\"1\""), std::string::npos);
    EXPECT_NE(s.find("Name=\"displacement_m\" NumberOfComponents=\"3\""), std::string::npos);
    EXPECT_NE(s.find("Name=\"velocity_m_per_s\" NumberOfComponents=\"3\""), std::string::npos);
    EXPECT_NE(s.find("Name=\"TimeValue\""), std::string::npos);
    EXPECT_NE(s.find("\n          4 2 0\n"), std::string::npos);  // last point, z padded with 0
    std::size_t open = 0, close = 0;
    for (auto p = s.find("<DataArray"); p != std::string::npos; p = s.find("<DataArray", p + 1)) ++open;
    for (auto p = s.find("</DataArray>"); p != std::string::npos; p = s.find("</DataArray>", p + 1)) ++close;
    EXPECT_EQ(open, 8u);  // TimeValue, 3 point arrays, Points, connectivity, offsets, types
    EXPECT_EQ(close, open);
    EXPECT_EQ(s.substr(s.size() - 11), "</VTKFile>\n");
}

TEST(IoVtu, RefinedGridShowsItsActiveNodesAndLevels)
{
    pd::RefinedGrid<2> g(pd::box<2>({{0, 0}}, {{3e-3, 2e-3}}, 1e-3), 3e-3);  // 3 x 2 cells
    g.split({0}, pd::Refinement::delta);                                    // cell 0 -> 4 level-1 cells: 9 active nodes
    const std::string path = temp_path("vtu/grid.vtu");
    pd::io::write_refined_grid_vtu(path, g, {{"ux_m", std::vector<double>(9, 1.0)}});
    EXPECT_THROW(pd::io::write_refined_grid_vtu(path, g, {{"ux_m", {1.0}}}), std::invalid_argument);
    const std::string s = slurp(path);
    EXPECT_NE(s.find("NumberOfPoints=\"9\""), std::string::npos);
    for (const char* name : {"level", "cell_side_m", "horizon_m", "ux_m"}) EXPECT_NE(s.find(std::string("Name=\"") + name + "\""), std::string::npos) << name;
    EXPECT_NE(s.find("\n          0.00025 0.00025 0\n"), std::string::npos);  // the first child, at the parent's centre - h/4
}

TEST(IoVtu, PvdIsValidAfterEachAdd)
{
    const std::string dir = temp_path("pvd/");
    pd::io::PvdWriter pvd(dir + "series.pvd");
    EXPECT_NE(slurp(dir + "series.pvd").find("<Collection>\n  </Collection>"), std::string::npos);
    pvd.add(0.0, dir + "s_0.vtu");
    pvd.add(1e-3, dir + "sub/s_1.vtu");
    const std::string s = slurp(dir + "series.pvd");
    EXPECT_NE(s.find("<DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"s_0.vtu\"/>"), std::string::npos) << s;
    EXPECT_NE(s.find("timestep=\"0.001\" group=\"\" part=\"0\" file=\"sub/s_1.vtu\""), std::string::npos) << s;
    EXPECT_FALSE(std::filesystem::exists(dir + "series.pvd.tmp"));
    EXPECT_EQ(pvd.size(), 2u);
}

TEST(IoTimer, TimerAndSilentProgress)
{
    pd::io::Timer timer;
    const double t1 = timer.seconds();
    EXPECT_GE(t1, 0.0);
    EXPECT_GE(timer.restart(), t1);
    EXPECT_LT(timer.seconds(), 60.0);

    ::testing::internal::CaptureStderr();
    {
        pd::io::Progress off("run", 100, false);
        EXPECT_FALSE(off.active());
        for (long n = 1; n <= 100; ++n) off.update(n);
        off.finish();
    }
    const char* ci = std::getenv("CI");
    const std::string saved = ci ? ci : "";
    setenv("CI", "1", 1);
    {
        pd::io::Progress in_ci("run", 100, true);  // CI set: silent even if stderr is a terminal
        EXPECT_FALSE(in_ci.active());
        in_ci.update(50);
    }
    if (ci) setenv("CI", saved.c_str(), 1);
    else unsetenv("CI");
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

}  // namespace
