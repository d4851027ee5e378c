// tests/test_io_csv.cpp -- pd::io CSV files: writer/reader round trip, rows on disk while written, a
// file under its name only when complete, the output manifest, the tolerant reader (BOM, CR, CRLF,
// blanks, comments) and the summary.csv header.
#include "pd/io/csv.hpp"

#include <gtest/gtest.h>

#include "io_fixtures.hpp"

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using pd_test::first_line;
using pd_test::slurp;
using pd_test::temp_path;

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
    EXPECT_EQ(slurp(path + ".part"), "a,b\n1.5,2.5\n");  // on disk while the writer is still open
    EXPECT_THROW(csv.row({1.0}), std::invalid_argument);
}

// A file takes its name only complete: under name.part while written, renamed at close() or when
// the writer goes out of scope, also while an exception unwinds (an unstable run keeps its rows);
// a rerun replaces the old file whole.
TEST(IoCsv, FileAppearsUnderItsNameOnlyWhenComplete)
{
    namespace fs = std::filesystem;
    const std::string path = temp_path("csv/pending.csv");
    fs::remove(path);
    {
        pd::io::CsvWriter csv(path, {"a"});
        csv.row({1.0});
        EXPECT_FALSE(fs::exists(path));
        EXPECT_TRUE(fs::exists(path + ".part"));
    }
    EXPECT_EQ(slurp(path), "a\n1\n");
    EXPECT_FALSE(fs::exists(path + ".part"));
    try {
        pd::io::CsvWriter csv(path, {"a"});
        csv.row({2.0});
        EXPECT_EQ(slurp(path), "a\n1\n");  // the previous run's file, whole, until this one is complete
        throw std::runtime_error("unstable");
    } catch (const std::runtime_error&) {
    }
    EXPECT_EQ(slurp(path), "a\n2\n");
    pd::io::CsvWriter csv(path, {"b"});
    csv.close();
    EXPECT_EQ(slurp(path), "b\n");
    EXPECT_FALSE(fs::exists(path + ".part"));
}

// A run into a folder first removes the files the previous run wrote there (its manifest), and only
// those: a file of the user's and names outside the folder stay.
TEST(IoCsv, OutputManifestRemovesThePreviousRunsFilesOnly)
{
    namespace fs = std::filesystem;
    const fs::path dir = temp_path("manifest");
    fs::remove_all(dir);
    fs::create_directories(dir / "sub");
    for (const char* f : {"old.csv", "old.csv.part", "sub/x.csv", "keep.txt"}) std::ofstream(dir / f) << "x\n";
    std::ofstream(temp_path("outside.csv")) << "x\n";
    std::ofstream(dir / pd::io::OutputManifest::name) << "old.csv\nsub/x.csv\n../outside.csv\n/etc/hostname\n";
    pd::io::OutputManifest::begin(dir);
    EXPECT_FALSE(fs::exists(dir / "old.csv"));
    EXPECT_FALSE(fs::exists(dir / "old.csv.part"));
    EXPECT_FALSE(fs::exists(dir / "sub/x.csv"));
    EXPECT_TRUE(fs::exists(dir / "keep.txt"));
    EXPECT_TRUE(fs::exists(temp_path("outside.csv")));
    EXPECT_EQ(slurp((dir / pd::io::OutputManifest::name).string()), "");
    { pd::io::CsvWriter csv(dir / "sub" / "new.csv", {"a"}); }
    { pd::io::CsvWriter csv(temp_path("elsewhere.csv"), {"a"}); }
    EXPECT_EQ(slurp((dir / pd::io::OutputManifest::name).string()), "sub/new.csv\n");
    pd::io::OutputManifest::begin(dir);  // the next run
    EXPECT_FALSE(fs::exists(dir / "sub" / "new.csv"));
    EXPECT_TRUE(fs::exists(dir / "keep.txt"));
}

TEST(IoCsv, ReaderToleratesByteOrderMarkAndCrLineEnds)
{
    const std::string path = temp_path("csv/bom_cr.csv");
    std::ofstream(path) << "\xEF\xBB\xBFx,y\r1,2\r\r3,4\r";
    const auto t = pd::io::read_csv(path);
    EXPECT_EQ(t.header, (std::vector<std::string>{"x", "y"}));
    ASSERT_EQ(t.rows.size(), 2u);
    EXPECT_EQ(t.rows[1].line, 4);
    EXPECT_EQ(t.rows[1].fields, (std::vector<std::string>{"3", "4"}));
    std::ofstream(path) << "x,y\n1,2,\n";
    try {
        pd::io::read_csv(path);
        ADD_FAILURE() << "a row with a trailing comma was read";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("bom_cr.csv:2: expected 2 fields, found 3 (a trailing comma?)"), std::string::npos) << e.what();
    }
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

}  // namespace
