// tests/test_io.cpp -- pd::io: options parsing and its exit-2 error contract, CSV writer/reader
// round trip, summary.csv and convergence.csv headers, observed convergence rate, VTU/PVD files,
// timer and progress display.
#include "pd/io/convergence.hpp"
#include "pd/io/csv.hpp"
#include "pd/io/options.hpp"
#include "pd/io/timer.hpp"
#include "pd/io/vtu.hpp"

#include <gtest/gtest.h>

#include "scratch_dir.hpp"

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

using pd::io::Options;

void parse(Options& opt, const std::vector<std::string>& args)
{
    std::vector<const char*> argv{"prog"};
    for (const auto& a : args) argv.push_back(a.c_str());
    opt.parse(static_cast<int>(argv.size()), argv.data());
}

// A path in this test's scratch directory; its parent directory exists.
std::string temp_path(const std::string& name)
{
    const auto p = pd_test::scratch_dir() / name;
    std::filesystem::create_directories(p.parent_path());
    return p.string();
}

std::string slurp(const std::string& path)
{
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string first_line(const std::string& path)
{
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    return line;
}

// A driver-like set of options: E, nu, m, model, T0 and the standard ones.
struct DriverOptions {
    Options opt{"prog", "test driver"};
    double& E = opt.add("E", 200e9, "Young's modulus", "Pa");
    double& nu = opt.add("nu", 0.25, "Poisson's ratio");
    double& T0 = opt.add("T0", 293.15, "initial temperature", "K");
    int& m = opt.add_int("m", 3, "horizon ratio delta/dx");
    std::string& model = opt.add_string("model", "lps", "material model", {"pmb", "lps"});
    DriverOptions()
    {
        pd::io::add_standard(opt, "reports/1d/test");
        opt.require_positive("E");
        opt.require_range("nu", -1.0, 0.5, false, false);
        opt.require_at_least("m", 1);
    }
};

void run(const std::vector<std::string>& args)
{
    DriverOptions d;
    parse(d.opt, args);
}

TEST(IoOptions, DefaultsWithoutArguments)
{
    DriverOptions d;
    parse(d.opt, {});
    EXPECT_EQ(d.E, 200e9);
    EXPECT_EQ(d.m, 3);
    EXPECT_EQ(d.model, "lps");
    EXPECT_FALSE(d.opt.get_flag("quick"));
    EXPECT_EQ(d.opt.get_string("out"), "reports/1d/test");
    EXPECT_EQ(d.opt.get_int("threads"), 0);
    EXPECT_FALSE(d.opt.given("E"));
}

TEST(IoOptions, ParsesSpaceAndEqualsForms)
{
    DriverOptions d;
    parse(d.opt, {"--E", "1.5e9", "--m=4", "--model", "pmb", "--quick", "--out=/tmp/x", "--T0", "-10",
                  "--check=false", "--nu=0.3"});
    EXPECT_EQ(d.E, 1.5e9);
    EXPECT_EQ(d.opt.get("E"), 1.5e9);
    EXPECT_EQ(d.m, 4);
    EXPECT_EQ(d.opt.get("m"), 4.0);  // get() reads int options too
    EXPECT_EQ(d.opt.get_string("model"), "pmb");
    EXPECT_TRUE(d.opt.get_flag("quick"));
    EXPECT_FALSE(d.opt.get_flag("check"));
    EXPECT_EQ(d.opt.get_string("out"), "/tmp/x");
    EXPECT_EQ(d.T0, -10.0);  // a negative number is a value, not an option
    EXPECT_EQ(d.nu, 0.3);
    EXPECT_TRUE(d.opt.given("E"));
    EXPECT_THROW(d.opt.get("nonexistent"), std::logic_error);  // programmer error, not input error
    EXPECT_THROW(d.opt.get_int("E"), std::logic_error);
}

TEST(IoOptions, EchoAndParamsCsv)
{
    Options opt("prog", "echo test");
    opt.add("E", 200e9, "Young's modulus", "Pa");
    opt.add("dx", 0.1, "grid spacing", "m");
    opt.add_int("m", 3, "horizon ratio");
    opt.add_string("label", "a,b", "text with a comma");
    opt.add_flag("quick", "coarse");
    parse(opt, {"--quick"});
    std::ostringstream os;
    opt.echo(os);
    EXPECT_EQ(os.str(), "  E = 2e+11 [Pa]\n  dx = 0.1 [m]\n  m = 3\n  label = a,b\n  quick = true\n");

    const std::string path = temp_path("options/params.csv");
    opt.save_csv(path);
    const auto t = pd::io::read_csv(path);
    ASSERT_EQ(t.header, (std::vector<std::string>{"option", "value", "unit"}));
    ASSERT_EQ(t.rows.size(), 5u);
    EXPECT_EQ(t.rows[0].fields, (std::vector<std::string>{"E", "2e+11", "Pa"}));
    EXPECT_EQ(t.rows[3].fields, (std::vector<std::string>{"label", "a,b", ""}));  // quoted on write
    EXPECT_EQ(t.rows[4].fields, (std::vector<std::string>{"quick", "true", ""}));
}

TEST(IoOptions, UsageListsDefaultsUnitsAndHelp)
{
    DriverOptions d;
    std::ostringstream os;
    d.opt.print_usage(os);
    const std::string u = os.str();
    EXPECT_NE(u.find("usage: prog"), std::string::npos);
    EXPECT_NE(u.find("test driver"), std::string::npos);
    EXPECT_NE(u.find("Young's modulus [Pa] (default 2e+11)"), std::string::npos);
    EXPECT_NE(u.find("--model {pmb,lps}"), std::string::npos);
    EXPECT_NE(u.find("--quick"), std::string::npos);
    EXPECT_NE(u.find("--help"), std::string::npos);
}

TEST(IoOptionsDeathTest, HelpExitsZero)
{
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(run({"--E", "bad", "--help"}), ::testing::ExitedWithCode(0), "");
}

TEST(IoOptionsDeathTest, InputErrorsExitTwoNamingTheOption)
{
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    using ::testing::ExitedWithCode;
    EXPECT_EXIT(run({"--bogus", "1"}), ExitedWithCode(2), "^prog: error: unknown option --bogus");
    EXPECT_EXIT(run({"--E", "abc"}), ExitedWithCode(2), "^prog: error: option --E expects a number, got 'abc'");
    EXPECT_EXIT(run({"--E=1e9x"}), ExitedWithCode(2), "option --E expects a number");
    EXPECT_EXIT(run({"--E", "inf"}), ExitedWithCode(2), "option --E expects a finite number");
    EXPECT_EXIT(run({"--E"}), ExitedWithCode(2), "^prog: error: option --E expects a value");
    EXPECT_EXIT(run({"--E", "--quick"}), ExitedWithCode(2), "option --E expects a value");
    EXPECT_EXIT(run({"--m", "2.5"}), ExitedWithCode(2), "option --m expects an integer");
    EXPECT_EXIT(run({"--model", "xyz"}), ExitedWithCode(2), "option --model must be one of pmb\\|lps");
    EXPECT_EXIT(run({"--quick=maybe"}), ExitedWithCode(2), "option --quick is a flag");
    EXPECT_EXIT(run({"stray"}), ExitedWithCode(2), "unexpected argument 'stray'");
}

TEST(IoOptionsDeathTest, InvalidValuesExitTwoNamingTheOption)
{
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    using ::testing::ExitedWithCode;
    EXPECT_EXIT(run({"--E", "-1"}), ExitedWithCode(2), "^prog: error: option --E must be > 0, got -1");
    EXPECT_EXIT(run({"--nu", "0.5"}), ExitedWithCode(2), "option --nu must be in \\(-1, 0.5\\), got 0.5");
    EXPECT_EXIT(run({"--m", "0"}), ExitedWithCode(2), "option --m must be >= 1, got 0");
    EXPECT_EXIT(run({"--threads", "-2"}), ExitedWithCode(2), "option --threads must be >= 0");
    EXPECT_EXIT(pd::io::fail_input("lib", "bad\nthing"), ExitedWithCode(2), "^lib: error: bad thing\n$");
}

TEST(IoOptionsDeathTest, RequireAfterParseChecksAtOnce)
{
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    Options opt("prog", "");
    opt.add("dt", -1.0, "time step", "s");
    parse(opt, {});
    EXPECT_EXIT(opt.require_positive("dt"), ::testing::ExitedWithCode(2), "option --dt must be > 0");
}

TEST(IoCsv, RoundTripIsBitExactWith17Digits)
{
    const std::vector<double> values{0.1, 1.0 / 3.0, -M_PI * 1e-300, 4.9406564584124654e-324, DBL_MAX,
                                     -1.2345678901234567e200, 2.0 / 7.0 * 1e-7, 0.0};
    const std::string path = temp_path("csv/roundtrip.csv");
    {
        pd::io::CsvWriter csv(path, {"name", "x_m", "n"});
        for (std::size_t k = 0; k < values.size(); ++k) csv.row({"v,\"q\"", values[k], static_cast<long>(k)});
        csv.row({"nan", std::nan(""), 7});
        EXPECT_EQ(csv.rows(), values.size() + 1);
    }
    const auto t = pd::io::read_csv(path);
    ASSERT_EQ(t.rows.size(), values.size() + 1);
    const auto x = t.numbers("x_m");
    for (std::size_t k = 0; k < values.size(); ++k) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(x[k]), std::bit_cast<std::uint64_t>(values[k])) << k;
        EXPECT_EQ(t.rows[k].fields[0], "v,\"q\"");
        EXPECT_EQ(t.rows[k].fields[2], std::to_string(k));
    }
    EXPECT_TRUE(std::isnan(x.back()));
    EXPECT_EQ(t.rows[1].line, 3);  // header on line 1
    EXPECT_EQ(pd::io::format_double(0.1), "0.10000000000000001");
}

TEST(IoCsv, WriterFlushesRowsAndChecksLength)
{
    const std::string path = temp_path("csv/flush.csv");
    pd::io::CsvWriter csv(path, {"a", "b"});
    csv.row(std::vector<double>{1.5, 2.5});
    EXPECT_EQ(slurp(path), "a,b\n1.5,2.5\n");  // on disk while the writer is still open
    EXPECT_THROW(csv.row({1.0}), std::invalid_argument);
}

TEST(IoCsv, ReaderToleratesCrlfBlanksAndComments)
{
    const std::string path = temp_path("csv/tolerant.csv");
    {
        std::ofstream out(path);
        out << "# a comment\r\n x , y \r\n\r\n 1, 2\r\n  # indented comment\n3,\"a,b\"  \n";
    }
    const auto t = pd::io::read_csv(path);
    EXPECT_EQ(t.header, (std::vector<std::string>{"x", "y"}));
    ASSERT_EQ(t.rows.size(), 2u);
    EXPECT_EQ(t.rows[0].line, 4);
    EXPECT_EQ(t.rows[0].fields, (std::vector<std::string>{"1", "2"}));
    EXPECT_EQ(t.rows[1].line, 6);
    EXPECT_EQ(t.rows[1].fields, (std::vector<std::string>{"3", "a,b"}));
    EXPECT_EQ(t.number(0, t.column("y")), 2.0);
    EXPECT_THROW(t.number(1, 1), std::runtime_error);    // "a,b" is not a number
    EXPECT_THROW(t.column("z"), std::runtime_error);

    {
        std::ofstream out(path);
        out << "x,y\n1,2\n\n3\n";
    }
    try {
        pd::io::read_csv(path);
        FAIL() << "a short row must be rejected";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("tolerant.csv:4: expected 2 fields, found 1"), std::string::npos)
            << e.what();
    }
}

TEST(IoCsv, SummaryHeaderAndAbsentReference)
{
    const std::string path = temp_path("csv/summary.csv");
    const double nan = std::nan("");
    pd::io::write_summary(path, {{"f1_Hz", 1000.5, 1000.0, pd::io::relative_error(1000.5, 1000.0), "Hz"},
                                 {"energy_J", 2.0, nan, nan, "J"}});
    EXPECT_EQ(first_line(path), "quantity,value,reference,rel_error,unit");
    const auto t = pd::io::read_csv(path);
    ASSERT_EQ(t.rows.size(), 2u);
    EXPECT_EQ(t.number(0, 3), 0.5 / 1000.0);
    EXPECT_EQ(t.rows[1].fields, (std::vector<std::string>{"energy_J", "2", "nan", "nan", "J"}));
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
