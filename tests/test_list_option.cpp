// tests/test_list_option.cpp -- pd::io::list_option: comma-separated numeric lists of one string
// option, in order; malformed, out-of-bound and empty lists end with status 2 and one line naming
// the option (the drivers' input-error contract).
#include "pd/io/list_option.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

using pd::io::ListValues;
using pd::io::Options;

// Parses `--sf text` and returns the list under `bound`.
std::vector<double> sf_list(const std::string& text, ListValues bound)
{
    Options opt("prog", "list test");
    opt.add_string("sf", "0.5", "safety factors, comma-separated");
    const std::string arg = "--sf=" + text;
    const char* argv[] = {"prog", arg.c_str()};
    opt.parse(2, argv);
    return pd::io::list_option(opt, "sf", bound);
}

TEST(IoListOption, ItemsInOrderExactly)
{
    // 1e-3 and 0.75e-3 must come back as the same doubles as the literals (round-trip parse).
    EXPECT_EQ(sf_list("1e-3,0.75e-3,1.5e-3", ListValues::positive), (std::vector<double>{1e-3, 0.75e-3, 1.5e-3}));
    EXPECT_EQ(sf_list("0.5", ListValues::positive), (std::vector<double>{0.5}));
    EXPECT_EQ(sf_list("0,0.002,0.02,0.2", ListValues::non_negative), (std::vector<double>{0, 0.002, 0.02, 0.2}));
}

TEST(IoListOptionDeathTest, BadItemsExitTwoNamingTheOption)
{
    EXPECT_EXIT(sf_list("0", ListValues::positive), ::testing::ExitedWithCode(2), "option --sf: '0' is not a positive number");
    EXPECT_EXIT(sf_list("0.5,abc", ListValues::positive), ::testing::ExitedWithCode(2), "option --sf: 'abc'");
    EXPECT_EXIT(sf_list("-1e-3", ListValues::non_negative), ::testing::ExitedWithCode(2), "option --sf: '-1e-3' is not a number >= 0");
    EXPECT_EXIT(sf_list("inf", ListValues::non_negative), ::testing::ExitedWithCode(2), "option --sf");
    EXPECT_EXIT(sf_list(",", ListValues::positive), ::testing::ExitedWithCode(2), "option --sf: '' is not");
    EXPECT_EXIT(sf_list("", ListValues::positive), ::testing::ExitedWithCode(2), "option --sf: empty list");
}

// Parses `--runs text` and returns the named choices among none|stretch|micro.
std::vector<std::string> runs_list(const std::string& text)
{
    Options opt("prog", "list test");
    opt.add_string("runs", "none", "runs, comma-separated");
    const std::string arg = "--runs=" + text;
    const char* argv[] = {"prog", arg.c_str()};
    opt.parse(2, argv);
    return pd::io::list_choices(opt, "runs", {"none", "stretch", "micro"});
}

TEST(IoListChoices, ItemsInOrder)
{
    EXPECT_EQ(runs_list("micro,none"), (std::vector<std::string>{"micro", "none"}));
    EXPECT_EQ(runs_list("stretch"), (std::vector<std::string>{"stretch"}));
}

TEST(IoListChoicesDeathTest, UnknownOrEmptyItemsExitTwo)
{
    EXPECT_EXIT(runs_list("micro,visco"), ::testing::ExitedWithCode(2), "option --runs: unknown item 'visco' \\(one of none\\|stretch\\|micro\\)");
    EXPECT_EXIT(runs_list(",micro"), ::testing::ExitedWithCode(2), "option --runs: unknown item ''");
    EXPECT_EXIT(runs_list(""), ::testing::ExitedWithCode(2), "option --runs: empty list");
}

}  // namespace
