// tests/test_io_options.cpp -- pd::io::Options: defaults, parsing forms, echo and params.csv, usage,
// and the exit-2 error contract (one line naming the option).
#include "pd/io/csv.hpp"
#include "pd/io/options.hpp"

#include <gtest/gtest.h>

#include "io_fixtures.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace {

using pd::io::Options;
using pd_test::temp_path;

void parse(Options& opt, const std::vector<std::string>& args)
{
    std::vector<const char*> argv{"prog"};
    for (const auto& a : args) argv.push_back(a.c_str());
    opt.parse(static_cast<int>(argv.size()), argv.data());
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
    // --out promises only what every driver writes; a driver writing VTU says so itself.
    EXPECT_NE(u.find("output folder (CSV files and params.csv)"), std::string::npos);
    EXPECT_EQ(u.find("VTU"), std::string::npos);
    Options vtu_driver{"prog", "writes VTU"};
    pd::io::add_standard(vtu_driver, "out", "output folder (CSV, params.csv, damage.vtu)");
    std::ostringstream os2;
    vtu_driver.print_usage(os2);
    EXPECT_NE(os2.str().find("output folder (CSV, params.csv, damage.vtu)"), std::string::npos);
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
    EXPECT_EXIT(run({"--T0", "1e308"}), ExitedWithCode(2), "^prog: error: option --T0 must be 0 or of magnitude 1e-30 to 1e30, got '1e308'");
    EXPECT_EXIT(run({"--T0", "-1e31"}), ExitedWithCode(2), "option --T0 must be 0 or of magnitude");
    EXPECT_EXIT(run({"--T0", "1e-31"}), ExitedWithCode(2), "option --T0 must be 0 or of magnitude");
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

}  // namespace
