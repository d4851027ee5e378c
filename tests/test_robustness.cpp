// Every executable against hostile numbers: each numeric option, found by parsing the program's
// --help (reals `--E X`, integers `--n N`, numeric comma lists `--dx-list TEXT`), is given
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
// Processes run in parallel (a few workers) under a wall-clock limit and are killed after it.
// PD_ROBUSTNESS_LOG=<file> writes every command with its status and stderr there.
#include <gtest/gtest.h>

#include "pd_run_harness.hpp"
#include "scratch_dir.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace {

namespace fs = std::filesystem;
using pd_test::slurp;
using Clock = std::chrono::steady_clock;

constexpr int workers = 4;                               // processes at once (2 cores: most runs wait in parse or are killed)
constexpr std::chrono::milliseconds run_limit{2500};     // a run still going after this has been accepted

// One process: argv, its stderr, how it ended.
struct Proc {
    std::vector<std::string> argv;
    int status = -1;      // exit status, or -1
    int signal = 0;       // terminating signal (not our kill)
    bool timed_out = false;
    std::chrono::milliseconds limit{0};  // this run's own limit (0: the caller's)
    std::string err;
};

std::string command_line(const std::vector<std::string>& argv)
{
    std::string s;
    for (const auto& a : argv) s += (s.empty() ? "" : " ") + (a.empty() ? std::string("''") : a);
    return s;
}

// Spawns argv with stdout to out_file (or /dev/null) and stderr to err_file; kills it after `limit`.
void execute(Proc& r, const fs::path& out_file, const fs::path& err_file, std::chrono::milliseconds limit)
{
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 1, out_file.empty() ? "/dev/null" : out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<char*> args;
    for (auto& a : r.argv) args.push_back(a.data());
    args.push_back(nullptr);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, args[0], &fa, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) {
        r.err = "posix_spawn failed: " + std::string(std::strerror(rc));
        return;
    }
    const auto deadline = Clock::now() + (r.limit.count() > 0 ? r.limit : limit);
    int ws = 0;
    while (true) {
        const pid_t w = waitpid(pid, &ws, WNOHANG);
        if (w == pid) break;
        if (Clock::now() > deadline) {
            kill(pid, SIGKILL);
            waitpid(pid, &ws, 0);
            r.timed_out = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(4));
    }
    if (!r.timed_out) {
        if (WIFEXITED(ws)) r.status = WEXITSTATUS(ws);
        else if (WIFSIGNALED(ws)) r.signal = WTERMSIG(ws);
    }
    r.err = slurp(err_file);
}

// Runs every Proc of `runs` on `workers` threads; run i writes below dir/i.
void execute_all(std::vector<Proc>& runs, const fs::path& dir, std::chrono::milliseconds limit)
{
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t i; (i = next++) < runs.size();) {
            const fs::path err = dir / ("case" + std::to_string(i) + ".err");
            execute(runs[i], {}, err, limit);
            fs::remove(err);
            std::error_code ec;
            fs::remove_all(dir / ("out" + std::to_string(i)), ec);  // --out of the case, if any
        }
    };
    std::vector<std::thread> pool;
    for (int w = 0; w < workers; ++w) pool.emplace_back(work);
    for (auto& t : pool) t.join();
}

int line_count(const std::string& s)
{
    int n = 0;
    for (char c : s) n += c == '\n';
    return n + (!s.empty() && s.back() != '\n');
}

bool ident(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'; }

// The message names option `name` as --name (not a prefix of a longer name) or 'name'.
bool names_option(const std::string& err, const std::string& name)
{
    for (std::size_t p = err.find("--" + name); p != std::string::npos; p = err.find("--" + name, p + 1)) {
        const std::size_t e = p + 2 + name.size();
        if (e == err.size() || !ident(err[e])) return true;
    }
    return err.find("'" + name + "'") != std::string::npos;
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

fs::path bin(const std::string& exe) { return fs::path(PD_BIN_DIR) / exe; }

// The help text of an executable (stdout of --help).
std::string help_of(const std::string& exe, const fs::path& dir)
{
    Proc r;
    r.argv = {bin(exe).string(), "--help"};
    const fs::path out = dir / (exe + ".help"), err = dir / (exe + ".help.err");
    execute(r, out, err, std::chrono::milliseconds(10000));
    EXPECT_EQ(r.status, 0) << exe << " --help: " << r.err;
    return slurp(out);
}

// Option lines of --help: "  --name X  help", "  --name N  help", "  --name TEXT  help".
void parse_help(Program& p, const std::string& help)
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

std::vector<std::string> argv_of(const Program& p, const Option& o, const std::string& value, const fs::path& out)
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
std::vector<Program> programs(const fs::path& dir)
{
    std::vector<Program> ps;
    std::ifstream list(fs::path(PD_BIN_DIR).parent_path() / "drivers.txt");
    for (std::string d; list >> d;) ps.emplace_back(d, Program::Args{{"threads", "1"}});
    EXPECT_GE(ps.size(), 25u) << "drivers.txt";
    // pd_run: a 6^3 lattice of 1 mm, steel, 10 steps.
    const fs::path cloud = dir / "cloud.csv";
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
void find_lists(std::vector<Program>& ps, const fs::path& dir)
{
    std::vector<std::pair<Program*, Option>> candidates;
    for (auto& p : ps)
        for (const auto& t : p.text_options) candidates.emplace_back(&p, Option{Option::list, t});
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
