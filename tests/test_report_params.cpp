// The committed results come from drivers whose options still match (issue 19: stale results fail).
// For every run folder reports/<dim>/<name>[/...] with a params.csv, the driver <name>_<dim> of this
// build, given the options that file records, must record the same options (--params-only writes its
// params.csv and exits without running): an option renamed, removed, added or validated differently
// since the run fails. The standard folders (reports/<dim>/<name>, and the runs of problems/verify.txt)
// must also hold what the driver records with exactly the arguments scripts/verify gives it (its
// defaults). Options that cannot change a result (threads, the step guard, checkpointing, --check)
// are left out of the comparison.
#include "pd/io/csv.hpp"

#include "pd_run_harness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path source = PD_SOURCE_DIR;

std::string shell_quoted(const std::string& s)
{
    std::string q = "'";
    for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    return q + "'";
}

// The params.csv that `exe args --params-only FILE` writes (its path; empty and `error` set on failure).
fs::path recorded(const std::string& exe, const std::string& args, const std::string& tag, std::string& error)
{
    const fs::path file = pd_test::base() / (tag + ".params.csv");
    fs::remove(file);
    const pd_test::Result r = pd_test::run_captured(exe, args + " --params-only " + file.string(), pd_test::base() / tag);
    if (r.status != 0 || !fs::exists(file)) {
        error = exe + " " + args + ": exit " + std::to_string(r.status) + ": " + r.err + r.out;
        return {};
    }
    return file;
}

// option -> value of a params.csv, without the options that cannot change a result (the step
// guard, threads, checkpointing, --check): a run made before such an option existed is not stale.
std::map<std::string, std::string> results_options(const fs::path& params)
{
    static const std::set<std::string> neutral{"threads", "max-steps", "checkpoint-every", "resume", "stop-after", "check"};
    std::map<std::string, std::string> out;
    for (const pd::io::CsvRow& r : pd::io::read_csv(params).rows)
        if (!neutral.count(r.fields.at(0))) out[r.fields.at(0)] = r.fields.at(1);
    return out;
}

// Options added to a driver after runs of it were committed, with the default that is the behaviour of
// those runs (the change that added each left every result of the driver bit-identical, checked with
// scripts/compare-quick): a run recorded before the option existed is not stale when the option is at
// this default. (driver, option) -> default.
const std::map<std::pair<std::string, std::string>, std::string> added_at_old_behaviour{
    {{"pals_units_3d", "pals-base"}, "normalised"},  // Peridigm's PALS base functions, an alternative
};

std::string differences(const std::string& exe, const fs::path& committed, const fs::path& now)
{
    const auto a = results_options(committed), b = results_options(now);
    std::string d;
    for (const auto& [k, v] : a)
        if (!b.count(k)) d += " --" + k + " (gone)";
        else if (b.at(k) != v) d += " --" + k + " " + v + " -> " + b.at(k);
    for (const auto& [k, v] : b) {
        const auto old = added_at_old_behaviour.find({exe, k});
        if (!a.count(k) && (old == added_at_old_behaviour.end() || old->second != v)) d += " --" + k + " (new: " + v + ")";
    }
    return d;
}

// The command line that reproduces a params.csv, as a user types it: --quick when it was given, then
// every option whose value differs from the driver's default (under that --quick); "" on failure.
std::string arguments_of(const std::string& exe, const fs::path& params, const std::string& tag, std::string& error)
{
    const auto committed = results_options(params);
    const bool quick = committed.at("quick") == "true";
    const fs::path defaults = recorded(exe, quick ? "--quick" : "", tag + ".defaults", error);
    if (!error.empty()) return "";
    const auto def = results_options(defaults);
    std::string args = quick ? " --quick" : "";
    for (const auto& [name, value] : committed) {
        if (name == "quick" || (def.count(name) && def.at(name) == value)) continue;
        args.append(" --").append(name);
        if (value != "true" && value != "false") args.append(" ").append(shell_quoted(value));
    }
    return args;
}

// The drivers of this build (build/drivers.txt).
std::vector<std::string> drivers()
{
    std::ifstream list(fs::path(PD_BIN_DIR).parent_path() / "drivers.txt");
    std::vector<std::string> out;
    for (std::string exe; list >> exe;) out.push_back(exe);
    return out;
}

// problems/verify.txt: the extra standard runs (`exe:arg:arg...`, with --out) and the standard
// arguments of drivers whose default is a full-size study (`standard:exe:arg...`).
std::map<fs::path, std::pair<std::string, std::string>> standard_runs()
{
    std::map<fs::path, std::pair<std::string, std::string>> runs;  // folder -> (exe, args)
    std::map<std::string, std::string> standard_args;
    std::ifstream verify(source / "problems/verify.txt");
    std::vector<std::vector<std::string>> extra;
    for (std::string line; std::getline(verify, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string item; std::getline(ss, item, ':');) f.push_back(item);
        if (f[0] == "standard") {
            std::string args;
            for (std::size_t k = 2; k < f.size(); ++k) args.append(" ").append(shell_quoted(f[k]));
            standard_args[f[1]] = args;
        } else {
            extra.push_back(f);
        }
    }
    for (const std::string& exe : drivers()) {
        const std::size_t u = exe.rfind('_');
        runs[source / "reports" / exe.substr(u + 1) / exe.substr(0, u)] = {exe, standard_args[exe]};
    }
    for (const auto& f : extra) {
        std::string args;
        fs::path out;
        for (std::size_t k = 1; k < f.size(); ++k) {
            if (f[k] == "--out" && k + 1 < f.size()) out = source / f[k + 1];
            args.append(" ").append(shell_quoted(f[k]));
        }
        runs[out] = {f[0], args};
    }
    return runs;
}

}  // namespace

TEST(ReportParams, EveryCommittedRunMatchesItsDriverOfThisBuild)
{
    const std::vector<std::string> list = drivers();
    const std::set<std::string> exes(list.begin(), list.end());
    ASSERT_GT(exes.size(), 20u) << "drivers.txt of the build lists the drivers";
    std::vector<std::string> stale;
    int checked = 0;
    for (const auto& e : fs::recursive_directory_iterator(source / "reports")) {
        if (e.path().filename() != "params.csv") continue;
        const fs::path rel = fs::relative(e.path(), source / "reports");
        auto it = rel.begin();
        const std::string dim = (it++)->string(), name = (it++)->string();
        const std::string exe = name + "_" + dim;
        if (!exes.count(exe)) {
            stale.push_back(rel.string() + ": no driver " + exe + " in this build");
            continue;
        }
        std::string error;
        const std::string tag = std::to_string(checked++), args = arguments_of(exe, e.path(), tag, error);
        const fs::path now = error.empty() ? recorded(exe, args, tag, error) : fs::path();
        if (!error.empty()) stale.push_back(rel.string() + ": its options do not run: " + error);
        else if (const std::string d = differences(exe, e.path(), now); !d.empty())
            stale.push_back(rel.string() + ": " + exe + " records other options today:" + d);
    }
    EXPECT_GT(checked, 20);
    for (const auto& [folder, run] : standard_runs()) {
        const fs::path params = folder / "params.csv";
        if (!fs::exists(params)) {
            stale.push_back(fs::relative(params, source).string() + ": the standard run of " + run.first + " is not committed");
            continue;
        }
        std::string error;
        const fs::path now = recorded(run.first, run.second, "std" + std::to_string(checked++), error);
        if (!error.empty()) stale.push_back(error);
        else if (const std::string d = differences(run.first, params, now); !d.empty())
            stale.push_back(fs::relative(params, source).string() + ": not the standard run " + run.first + run.second + ":" + d);
    }
    std::string all;
    for (const std::string& s : stale) all += "\n  " + s;
    EXPECT_TRUE(stale.empty()) << stale.size() << " stale run folder(s):" << all;
}
