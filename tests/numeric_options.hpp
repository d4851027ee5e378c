// The numeric options of the build's executables (test_robustness.cpp): the drivers of build/drivers.txt
// plus pd_run (on a small lattice cloud), pd_bench and damage_cost with their cheapest valid arguments;
// reals (X) and integers (N) from --help, numeric lists among the TEXT options by probing with "zzz".
#pragma once

#include <gtest/gtest.h>

#include "pd_run_harness.hpp"
#include "process_pool.hpp"

#include <cctype>
#include <chrono>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace pd_test::numeric_options {

using namespace pd_test::process_pool;

inline constexpr std::chrono::milliseconds run_limit{2500};  // a run still going after this has been accepted

inline bool ident(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'; }

// The message names option `name` as --name (not a prefix of a longer name) or 'name'.
inline bool names_option(const std::string& err, const std::string& name)
{
    for (std::size_t p = err.find("--" + name); p != std::string::npos; p = err.find("--" + name, p + 1)) {
        const std::size_t e = p + 2 + name.size();
        if (e == err.size() || !ident(err[e])) return true;
    }
    return err.find("'" + name + "'") != std::string::npos;
}

// A numeric option from --help.
struct Option {
    enum Kind { real, integer, list } kind;
    std::string name;
    std::string partner = {};  // a list option that must be given with this one ("--deltas and --ms go together")
};

struct Program {
    using Args = std::vector<std::pair<std::string, std::string>>;
    Program(std::string n, Args b) : name(std::move(n)), base(std::move(b)) {}
    std::string name;
    Args base;  // cheapest valid arguments (value "" = flag)
    bool has_out = false;
    std::vector<Option> options;
    std::vector<std::string> text_options;  // TEXT options other than --out (candidate lists)
};

inline std::filesystem::path bin(const std::string& exe) { return std::filesystem::path(PD_BIN_DIR) / exe; }

// The help text of an executable (stdout of --help).
inline std::string help_of(const std::string& exe, const std::filesystem::path& dir)
{
    Proc r;
    r.argv = {bin(exe).string(), "--help"};
    const std::filesystem::path out = dir / (exe + ".help"), err = dir / (exe + ".help.err");
    execute(r, out, err, std::chrono::milliseconds(10000));
    EXPECT_EQ(r.status, 0) << exe << " --help: " << r.err;
    return pd_test::slurp(out);
}

// Option lines of --help: "  --name X  help", "  --name N  help", "  --name TEXT  help".
inline void parse_help(Program& p, const std::string& help)
{
    static const std::regex line(R"(^\s+--([A-Za-z0-9][A-Za-z0-9_-]*)(\s+(X|N|TEXT)\b)?.*$)");
    std::istringstream in(help);
    for (std::string s; std::getline(in, s);) {
        std::smatch m;
        if (!std::regex_match(s, m, line)) continue;
        const std::string name = m[1], kind = m[3];
        if (name == "out") p.has_out = true;
        if (kind == "X") p.options.push_back({Option::real, name});
        else if (kind == "N") p.options.push_back({Option::integer, name});
        else if (kind == "TEXT" && name != "out") p.text_options.push_back(name);
    }
}

inline std::vector<std::string> argv_of(const Program& p, const Option& o, const std::string& value, const std::filesystem::path& out)
{
    std::vector<std::string> a{bin(p.name).string()};
    for (const auto& [k, v] : p.base) {
        if (k == o.name) continue;
        a.push_back("--" + k);
        if (!v.empty()) a.push_back(v);
    }
    if (!o.partner.empty()) a.insert(a.end(), {"--" + o.partner, "1"});
    a.push_back("--" + o.name);
    a.push_back(value);
    if (p.has_out) {
        a.push_back("--out");
        a.push_back(out.string());
    }
    return a;
}

// The executables and their cheapest valid runs.
inline std::vector<Program> programs(const std::filesystem::path& dir)
{
    std::vector<Program> ps;
    std::ifstream list(std::filesystem::path(PD_BIN_DIR).parent_path() / "drivers.txt");
    for (std::string d; list >> d;) ps.emplace_back(d, Program::Args{{"threads", "1"}});
    EXPECT_GE(ps.size(), 25u) << "drivers.txt";
    // pd_run: a 6^3 lattice of 1 mm, steel, 10 steps.
    const std::filesystem::path cloud = dir / "cloud.csv";
    std::ofstream(cloud) << pd_test::lattice_csv(6, 1e-3, "", [](int, int, int) { return std::string(); });
    ps.emplace_back("pd_run", Program::Args{{"input", cloud.string()}, {"E", "200e9"}, {"nu", "0.25"}, {"rho", "7800"},
                                            {"delta", "3.015e-3"}, {"steps", "10"}, {"threads", "1"}});
    ps.emplace_back("pd_bench", Program::Args{{"n", "6"}, {"steps", "5"}, {"threads", "1"}});
    ps.emplace_back("damage_cost", Program::Args{{"block", "2"}, {"blocks", "2"}, {"threads", "1"}});
    for (auto& p : ps) {
        const std::string help = help_of(p.name, dir);
        if (help.find("\n  --quick ") != std::string::npos) p.base.insert(p.base.begin(), {"quick", ""});
        parse_help(p, help);
    }
    return ps;
}

// TEXT options that are numeric lists: the program, given "zzz", says it is not a number. An
// option that must come with another one (the message names it) is probed again with the other = 1.
inline void find_lists(std::vector<Program>& ps, const std::filesystem::path& dir)
{
    std::vector<std::pair<Program*, Option>> candidates;
    for (auto& p : ps)
        for (const auto& t : p.text_options)
            if (t != "params-only") candidates.emplace_back(&p, Option{Option::list, t});  // a file it would write, not a list
    for (int round = 0; round < 2 && !candidates.empty(); ++round) {
        std::vector<Proc> probes(candidates.size());
        for (std::size_t k = 0; k < probes.size(); ++k)
            probes[k].argv = argv_of(*candidates[k].first, candidates[k].second, "zzz", dir / ("out" + std::to_string(k)));
        execute_all(probes, dir, run_limit);
        std::vector<std::pair<Program*, Option>> again;
        for (std::size_t k = 0; k < probes.size(); ++k) {
            auto& [p, o] = candidates[k];
            if (probes[k].status != 2 || !names_option(probes[k].err, o.name)) continue;
            if (probes[k].err.find("number") != std::string::npos) {
                p->options.push_back(o);
                continue;
            }
            for (const auto& u : p->text_options)
                if (round == 0 && u != o.name && names_option(probes[k].err, u)) again.emplace_back(p, Option{Option::list, o.name, u});
        }
        candidates = again;
    }
}

}  // namespace pd_test::numeric_options
