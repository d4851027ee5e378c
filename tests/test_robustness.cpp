// Every executable against hostile numbers: each numeric option, found by parsing the program's
// --help (reals `--E X`, integers `--n N`, numeric comma lists `--dx-list TEXT`: numeric_options.hpp),
// is given
//   nan, inf, 1e308 (and 2147483648, 99999999999999999999 for integers): exit 2 with ONE stderr
//     line naming the option (the command line accepts only finite reals of magnitude 1e-30..1e30
//     and ints in range; lib/pd/io/options.hpp);
//   -1 and 0: any of the contract's statuses 0, 2, 3 (never a signal; 1 only means a failed
//     --check, which is never given here); a run still going after a short timeout has started and
//     counts as accepted. Exit 2 and 3 must still be one line; an exit-2 line must name the option
//     (as --name, 'name' or a bare word) or another option the user can act on; those without
//     --name or 'name' are printed.
// The executables are the drivers of build/drivers.txt plus pd_run (on a small lattice cloud),
// pd_bench and damage_cost, each with its cheapest valid arguments (--quick, --threads 1, ...).
// Processes run in parallel (a few workers) under a wall-clock limit and are killed after it
// (process_pool.hpp). PD_ROBUSTNESS_LOG=<file> writes every command with its status and stderr there.
#include <gtest/gtest.h>

#include "numeric_options.hpp"
#include "process_pool.hpp"
#include "scratch_dir.hpp"

#include <cctype>
#include <chrono>
#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using namespace pd_test::numeric_options;
using namespace pd_test::process_pool;

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

int line_count(const std::string& s)
{
    int n = 0;
    for (char c : s) n += c == '\n';
    return n + (!s.empty() && s.back() != '\n');
}

// Weaker, for values that are valid numbers: the message names the option as a bare word ("nu
// must lie in ...") or some other option the user can change ("--delta", "--dx").
bool names_something(const std::string& err, const std::string& name)
{
    for (std::size_t p = err.find(name); p != std::string::npos; p = err.find(name, p + 1)) {
        const std::size_t e = p + name.size();
        if ((p == 0 || !ident(err[p - 1])) && (e == err.size() || !ident(err[e]))) return true;
    }
    for (std::size_t p = err.find("--"); p != std::string::npos; p = err.find("--", p + 1))
        if (p + 2 < err.size() && std::isalpha(static_cast<unsigned char>(err[p + 2]))) return true;
    return false;
}

const char* kind_name(Option::Kind k) { return k == Option::real ? "X" : k == Option::integer ? "N" : "list"; }

}  // namespace

TEST(Robustness, EveryNumericOptionOfEveryExecutable)
{
    const auto t0 = Clock::now();
    const fs::path dir = pd_test::scratch_dir();
    std::vector<Program> ps = programs(dir);
    find_lists(ps, dir);
    for (const auto& p : ps) EXPECT_FALSE(p.options.empty()) << p.name << ": no numeric option found in --help";

    struct Case {
        const Program* program;
        Option option;
        std::string value;
        bool must_reject;  // nan, inf, 1e308, oversized integers
    };
    std::vector<Case> cases;
    // Values that may start a run first (they take the longest), then those rejected at parse.
    for (const auto& p : ps)
        for (const auto& o : p.options)
            for (const char* v : {"-1", "0"}) cases.push_back({&p, o, v, false});
    for (const auto& p : ps)
        for (const auto& o : p.options) {
            for (const char* v : {"nan", "inf", "1e308"}) cases.push_back({&p, o, v, true});
            if (o.kind == Option::integer)
                for (const char* v : {"2147483648", "99999999999999999999"}) cases.push_back({&p, o, v, true});
        }
    std::vector<Proc> runs(cases.size());
    for (std::size_t i = 0; i < cases.size(); ++i) {
        runs[i].argv = argv_of(*cases[i].program, cases[i].option, cases[i].value, dir / ("out" + std::to_string(i)));
        // A value rejected at parse exits within milliseconds; a loaded machine (parallel ctest,
        // sanitizers) may delay its start, which must not read as a run that went on.
        if (cases[i].must_reject) runs[i].limit = std::chrono::seconds(30);
    }
    execute_all(runs, dir, run_limit);

    std::size_t options = 0, timed_out = 0;
    std::map<int, std::size_t> statuses;
    for (const auto& p : ps) options += p.options.size();
    std::ostringstream unnamed;  // exit 2 on -1 / 0 whose line does not name the option
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const Case& c = cases[i];
        const Proc& r = runs[i];
        const std::string what = command_line(r.argv) + "\n  status " +
                                 (r.timed_out ? "running after " + std::to_string(run_limit.count()) + " ms (killed)"
                                  : r.signal ? "signal " + std::to_string(r.signal)
                                             : std::to_string(r.status)) +
                                 ", stderr:\n" + r.err;
        timed_out += r.timed_out;
        if (!r.timed_out && !r.signal) ++statuses[r.status];
        if (c.must_reject) {
            EXPECT_TRUE(r.status == 2 && line_count(r.err) == 1 && names_option(r.err, c.option.name))
                << "[" << kind_name(c.option.kind) << " --" << c.option.name << " " << c.value << "] " << what;
            continue;
        }
        EXPECT_EQ(r.signal, 0) << "[signal] " << what;
        EXPECT_TRUE(r.timed_out || r.signal || r.status == 0 || r.status == 2 || r.status == 3)
            << "[exit " << r.status << " without --check] " << what;
        if (r.status == 2 || r.status == 3) {
            EXPECT_EQ(line_count(r.err), 1) << "[exit " << r.status << ", not one line] " << what;
        }
        if (r.status == 2 && !names_option(r.err, c.option.name)) {
            EXPECT_TRUE(names_something(r.err, c.option.name)) << "[exit 2, names no option] " << what;
            unnamed << what;
        }
    }
    if (const char* log = std::getenv("PD_ROBUSTNESS_LOG")) {  // every run, for a reader of the whole table
        std::ofstream out(log);
        for (std::size_t i = 0; i < cases.size(); ++i)
            out << command_line(runs[i].argv) << "\n  "
                << (runs[i].timed_out ? "killed after " + std::to_string(run_limit.count()) + " ms"
                    : runs[i].signal  ? "signal " + std::to_string(runs[i].signal)
                                      : "exit " + std::to_string(runs[i].status))
                << ": " << runs[i].err << (runs[i].err.ends_with('\n') ? "" : "\n");
    }
    const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
    std::cout << ps.size() << " executables, " << options << " numeric options, " << cases.size() << " runs ("
              << timed_out << " still running after " << run_limit.count() << " ms);";
    for (const auto& [s, n] : statuses) std::cout << " exit " << s << ": " << n << ";";
    std::cout << " wall " << wall << " s\n";
    if (!unnamed.str().empty()) std::cout << "exit 2 on -1 / 0 without --name or 'name':\n" << unnamed.str();
    fs::remove_all(dir);
}
