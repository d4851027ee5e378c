// pd/io/case.hpp -- the plumbing of a problem driver, in one object: options (the standard
// --quick --check --out --threads are added by parse), echo, params.csv, threads, the --check list, summary.csv, the
// verdict line and the exit status. A driver keeps only its physics steps:
//
//     pd::io::Case run("agwai_bar_1d", "1D conduction, Agwai PD vs classical.", "reports/1d/agwai_bar");
//     double& k = run.opt.add("k", 50, "thermal conductivity", "W/(m K)");
//     run.opt.require_positive("k");
//     run.start(argc, argv);                      // parse, check --out, echo, params.csv, threads
//                                                 // (or run.parse(argc, argv); quick defaults; run.start();)
//     ...                                          // the physics, CSVs under run.out()
//     run.check(rate > 0.9, "first-order convergence");
//     run.summary({"t50", t, t_ref, pd::io::relative_error(t, t_ref), "s"});
//     return run.finish("t50 %.3f s (classical %.3f s)", t, t_ref);   // summary.csv, verdict, 0 or 1
//
// Exit status (with guarded_main): 0 done, 1 a --check failed, 2 invalid input, 3 unstable run.
// --out must name a folder that can be created (not empty, not an existing file): otherwise the
// one-line message and status 2, before any computation. The files a previous run wrote there
// (its OutputManifest, csv.hpp) are removed first, so that the folder holds one run's files.
// --threads is at most 4x the processors (above the processors: a warning).
// allow_checkpoints(): the driver's time loops are restartable (io/checkpoints.hpp).
#pragma once
#include "pd/io/checkpoints.hpp"
#include "pd/io/checks.hpp"
#include "pd/io/csv.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/options.hpp"
#include "pd/core/errors.hpp"
#include "pd/core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

namespace pd::io {

// The largest --threads accepted: oversubscription beyond 4 threads per processor only slows a run
// down (and thousands of threads exhaust the system's thread limit).
inline int processors() { return static_cast<int>(std::thread::hardware_concurrency()); }  // 0 when unknown
inline int max_threads() { return 4 * std::max(processors(), 1); }

class Case {
public:
    Options opt;
    int quick_threads = 0;  // OpenMP threads of a --quick run without --threads (0: as --threads' default)

    // out_help: the help text of --out (a driver that writes more than CSV files says so there).
    Case(std::string program, std::string description, const std::string& default_out,
         const std::string& out_help = "output folder (CSV files and params.csv)")
        : opt(std::move(program), std::move(description)), default_out_(default_out), out_help_(out_help)
    {
    }

    // Parses argv (exit 0 on --help, 2 on an input error), creates --out (exit 2 when it cannot
    // be), echoes the options, writes params.csv and sets the OpenMP threads (quick_threads for a
// --quick run without --threads, when set). A driver whose
    // defaults depend on --quick (or on other options) calls parse(), sets them, then start().
    void start(int argc, const char* const* argv)
    {
        parse(argc, argv);
        start();
    }
    // The options that set the time scale of the driver's heat or ODE problem ("--k, --rho, --c"),
    // named when CVODE cannot take its first step on it (guarded_main, exit status 2).
    void time_scale_set_by(const std::string& options) { time_scale_options() = options; }

    // A driver whose time loops save their state (io/checkpoints.hpp) calls this before parse():
    // it adds --checkpoint-every, --resume and --stop-after.
    void allow_checkpoints() { checkpoints_allowed_ = true; }
    Checkpoints& checkpoints() { return checkpoints_; }

    // The standard options are registered here, after the driver's own (so they close --help and
    // params.csv).
    void parse(int argc, const char* const* argv)
    {
        add_standard(opt, default_out_, out_help_);
        if (checkpoints_allowed_) {
            opt.add_int("checkpoint-every", 0, "also a checkpoint every N steps of each time loop (0: at the end of each loop and when stopped)");
            opt.add_flag("resume", "continue the stopped run whose checkpoints are in --out (same options)");
            opt.add_int("stop-after", 0, "stop after this many steps, with a checkpoint, as on SIGINT (0: never)");
            for (const char* o : {"checkpoint-every", "stop-after"}) opt.require_at_least(o, 0);
        }
        opt.add_string("params-only", "", "write the params.csv this run would record to FILE and exit without running");
        opt.not_recorded("params-only");
        opt.require_range("threads", 0, max_threads());
        opt.parse(argc, argv);
        quick_ = opt.get_flag("quick");
        check_mode_ = opt.get_flag("check");
    }
    void start()
    {
        if (const std::string params = opt.get_string("params-only"); !params.empty()) {  // nothing in --out is touched
            opt.save_csv(params);
            std::exit(0);
        }
        out_ = opt.get_string("out");
        if (out_.empty()) opt.fail("option --out must not be empty");
        std::error_code ec;
        std::filesystem::create_directories(out_, ec);
        if (ec || !std::filesystem::is_directory(out_)) opt.fail("option --out: cannot create the folder '" + out_.string() + "'");
        const bool resume = checkpoints_allowed_ && opt.get_flag("resume");
        if (checkpoints_allowed_) {
            try {
                checkpoints_.configure(opt.get_int("checkpoint-every"), resume, opt.get_int("stop-after"), out_,
                                       options_fingerprint(opt, {"out", "threads", "check", "max-steps", "checkpoint-every", "resume", "stop-after"}));
            } catch (const std::invalid_argument& e) {
                opt.fail(e.what());
            }
        }
        opt.echo(std::cout);
        try {
            if (resume) OutputManifest::resume(out_);  // keeps the checkpoints and files of the run it continues
            else OutputManifest::begin(out_);          // removes the files of the previous run into out_ (csv.hpp)
            opt.save_csv(out_ / "params.csv");
        } catch (const std::exception& e) {
            opt.fail("option --out: " + std::string(e.what()));
        }
        step_limit() = opt.get_int("max-steps");
        const int threads = opt.get_int("threads");
        if (processors() > 0 && threads > processors())
            std::fprintf(stderr, "%s: warning: --threads %d is more than the %d processors (oversubscription slows the run)\n",
                         opt.program().c_str(), threads, processors());
        set_threads(quick_ && quick_threads > 0 && !opt.given("threads") ? quick_threads : threads);
    }

    bool quick() const { return quick_; }
    // The coarse value of an option under --quick, unless the user gave it (between parse() and
    // start(): params.csv records the value that runs). --quick never overrides a given value.
    template <class V>
    void quick_default(const std::string& name, const V& value)
    {
        if (quick_) opt.set_default(name, value);
    }
    const std::filesystem::path& out() const { return out_; }
    std::filesystem::path file(const std::string& name) const { return out_ / name; }

    // One line of the --check list ("check: <what> ok|FAILED"), by kind (io/checks.hpp): against an
    // independent reference, a qualitative property or invariant, or a bound from our own earlier output.
    void check(bool ok, const std::string& what) { checks_(ok, what, CheckKind::accuracy); }
    void property(bool ok, const std::string& what) { checks_(ok, what, CheckKind::property); }
    void regression_bound(bool ok, const std::string& what) { checks_(ok, what, CheckKind::regression_bound); }
    bool passed() const { return checks_.passed(); }

    // A headline result for summary.csv (written by finish, in the order given).
    void summary(SummaryRow row) { rows_.push_back(std::move(row)); }
    void summary(const std::vector<SummaryRow>& rows) { rows_.insert(rows_.end(), rows.begin(), rows.end()); }
    // Rows of features a run may not show (a crack that does not start, a branch or a second peak
    // that does not form): there a nan value means "not observed" (a not_measured row), which the
    // driver's --check list reports; any other row must be finite (finish).
    void summary_observed(std::vector<SummaryRow> rows)
    {
        for (SummaryRow& r : rows) r.measured = r.measured && !std::isnan(r.value);
        summary(rows);
    }
    const std::vector<SummaryRow>& summary_rows() const { return rows_; }
    // The summary as the drivers' table on stdout.
    void print_summary(int name_width, int digits = 6) const { pd::io::print_summary(rows_, name_width, digits); }

    // Writes summary.csv (when there are rows) and checks.csv (check,kind,passed: every check of the
    // run with its kind and 1 or 0, whether or not --check is given), prints `verdict: PASS|FAIL: <headline>` and returns
    // the exit status: 1 when --check is given and a check failed, else 0. A measured row whose value
    // is nan or inf throws NonFiniteResult naming it (status 3 with guarded_main), after summary.csv
    // is written; a quantity the run does not measure is a not_measured row (csv.hpp).
    [[gnu::format(printf, 2, 3)]] int finish(const char* headline, ...)
    {
        if (!rows_.empty()) write_summary(out_ / "summary.csv", rows_);
        if (!checks_.list().empty()) {  // the --check list with its outcomes (the ledger reads it: tools/ledger.cpp)
            CsvWriter csv(out_ / "checks.csv", {"check", "kind", "passed"});
            for (const CheckRecord& c : checks_.list()) csv.row({c.what, kind_name(c.kind), c.ok ? 1 : 0});
        }
        checkpoints_.remove_all();  // the run is complete
        for (const SummaryRow& r : rows_)
            if (r.measured && !std::isfinite(r.value))
                throw NonFiniteResult("non-finite result: " + r.quantity + " = " + (std::isnan(r.value) ? "nan" : r.value > 0 ? "inf" : "-inf") +
                                      " (summary.csv written; the run's numbers are not to be trusted)");
        char text[1024];
        va_list args;
        va_start(args, headline);
        std::vsnprintf(text, sizeof text, headline, args);
        va_end(args);
        std::printf("verdict: %s: %s\n", passed() ? "PASS" : "FAIL (see the checks above)", text);
        return exit_status();
    }
    int exit_status() const { return check_mode_ && !passed() ? 1 : 0; }

private:
    std::string default_out_, out_help_;
    std::filesystem::path out_;
    Checks checks_;
    std::vector<SummaryRow> rows_;
    bool quick_ = false, check_mode_ = false, checkpoints_allowed_ = false;
    Checkpoints checkpoints_;
};

}  // namespace pd::io
