// pd/io/checkpoints.hpp -- restartable drivers: a run's state saved between steps
// (core/state_archive.hpp), the stop signals, and the fingerprint that ties a checkpoint to the
// options of the run that wrote it.
//
// A driver that calls Case::allow_checkpoints() before parsing gets three options:
//   --checkpoint-every N   also a checkpoint every N steps of each time loop (0: only at the end of
//                          each loop and when stopped)
//   --resume               continue the run whose checkpoints are in --out (same options)
//   --stop-after N         stop after N steps of this process as on SIGINT (0: never), e.g. for a
//                          batch slot of known length
// and runs each of its time loops (one per dx, seed, model or table cell: the driver's k-th loop
// keeps its checkpoint in <out>/checkpoint_<k>.pdstate) through loop(), with one state function
// used in both directions:
//
//     auto state = [&](pd::StateArchive& ar) { sim.state(ar), tips.state(ar, "tips"), csv.state(ar); };
//     run.checkpoints().loop(steps, state, [&] { sim.start(); }, [&](long n) {
//         sim.step(dt);
//         ...                                             // samples, CSV rows
//         return true;                                    // false: the loop ends here
//     });
//
// SIGINT or SIGTERM stops a loop after the step in progress with a checkpoint (pd::Interrupted,
// exit status 128 + signal; a second signal ends the process at once, e.g. during a long set-up,
// where the first is only seen after the first step); the files still open keep their ".part"
// names, the finished ones theirs. The end of each loop stores its final state, so that a resumed
// driver redoes only the measurements of the loops that had finished (they take no step) and goes
// on with the one that was stopped: its files then equal those of the uninterrupted run (wall times
// apart; params.csv records --resume). A CsvWriter that a loop fills is part of its state
// (CsvWriter::state). Case::finish removes the checkpoints of a completed driver, a failing driver
// its own, a new run into the folder stale ones.
#pragma once
#include "pd/core/errors.hpp"
#include "pd/core/state_archive.hpp"
#include "pd/io/csv.hpp"
#include "pd/io/options.hpp"

#include <csignal>
#include <exception>
#include <filesystem>
#include <initializer_list>
#include <sstream>
#include <string>
#include <system_error>

namespace pd::io {

// The signal that asked the run to stop (SIGINT, SIGTERM); 0 while none did.
inline volatile std::sig_atomic_t stop_signal = 0;
// The first signal asks the run to stop after its step; a second one ends it at once (the default
// action), for a step or a set-up that takes too long. Both calls are async-signal-safe.
inline void on_stop_signal(int sig)
{
    if (stop_signal != 0) {
        std::signal(sig, SIG_DFL);
        std::raise(sig);
    }
    stop_signal = sig;
}
inline void catch_stop_signals()
{
    std::signal(SIGINT, on_stop_signal);
    std::signal(SIGTERM, on_stop_signal);
}
inline const char* signal_name(int sig) { return sig == SIGINT ? "SIGINT" : sig == SIGTERM ? "SIGTERM" : "a signal"; }

// The options of a run as text, one "name = value" line each, but those in `free` (what a restart
// may change: output folder, threads, checkpoint cadence, ...).
inline std::string options_fingerprint(const Options& opt, std::initializer_list<const char*> free)
{
    std::ostringstream text, out;
    opt.echo(text);
    std::istringstream echo(text.str());
    for (std::string line; std::getline(echo, line);) {
        const std::size_t a = line.find_first_not_of(' '), b = line.find(" = ");
        bool skip = false;
        if (a != std::string::npos && b != std::string::npos)
            for (const char* f : free) skip = skip || line.substr(a, b - a) == f;
        if (!skip) out << line << '\n';
    }
    return out.str();
}

// The first line in which two fingerprints differ, for the message of a refused restart.
inline std::string first_difference(const std::string& saved, const std::string& now)
{
    std::istringstream a(saved), b(now);
    std::string la, lb;
    auto shown = [](bool got, const std::string& line) {
        const std::size_t a = line.find_first_not_of(' ');
        return got && a != std::string::npos ? line.substr(a) : std::string("-");
    };
    while (true) {
        const bool ga = static_cast<bool>(std::getline(a, la)), gb = static_cast<bool>(std::getline(b, lb));
        if (!ga && !gb) return "";
        if (!ga || !gb || la != lb) return std::string("'") + shown(ga, la) + "' in the checkpoint, '" + shown(gb, lb) + "' in this run";
    }
}

class Checkpoints {
public:
    Checkpoints() = default;
    Checkpoints(const Checkpoints&) = delete;
    Checkpoints& operator=(const Checkpoints&) = delete;
    // A driver that fails (an unstable run, a bad input found late, a write error) leaves no
    // checkpoint behind: there is nothing to resume. A stop (pd::Interrupted) keeps them.
    ~Checkpoints()
    {
        if (std::uncaught_exceptions() > 0 && !stopping_to_resume()) remove_all();
    }

    // Set by Case::start: every (steps, 0 = none), resume, stop_after (steps of this process, 0 =
    // never), the output folder and the options' fingerprint. Installs the signal handlers.
    void configure(long every, bool resume, long stop_after, const std::filesystem::path& out, std::string fingerprint)
    {
        every_ = every, resume_ = resume, stop_after_ = stop_after, out_ = out, fingerprint_ = std::move(fingerprint);
        enabled_ = true;
        catch_stop_signals();
        if (!resume_) return;
        if (!std::filesystem::exists(file(0)))
            throw std::invalid_argument("option --resume: no checkpoint in '" + out_.string() + "' (" + file(0).filename().string() + ")");
        read(0);  // refused before any file in the folder changes
    }

    // One restartable time loop (header): under --resume, and when this loop has a checkpoint,
    // state(ar) loads it; start() when the loop starts from step 0; step(n) for n = first + 1, ...,
    // steps (a false return ends the loop after that step: a loop that ends on a condition); after
    // each step a checkpoint on the cadence, or on a stop signal (or after --stop-after steps) a
    // checkpoint and pd::Interrupted; after the last step the loop's final state. A loop whose final
    // state is loaded takes no step (its measurements are redone). Returns the last step's number.
    // An exception from step() (pd::Unstable) leaves no final state: a resumed driver repeats the
    // loop from its last checkpoint, deterministically to the same end. Without Case::allow_checkpoints
    // (not configured) it is a plain loop.
    template <class State, class Start, class Step>
    long loop(long steps, State&& state, Start&& start, Step&& step)
    {
        const Resumed at = begin(state);
        if (at.complete) return at.step;
        if (at.step == 0) start();
        long n = at.step;
        while (n < steps) {
            if (!step(++n)) break;
            after_step(at, n, state);
        }
        end(at, n, state);
        return n;
    }

    // The driver has finished: its checkpoints are removed.
    void remove_all() const
    {
        if (!enabled_) return;
        std::error_code ec;
        for (int k = 0; k < next_; ++k) {
            std::filesystem::path part = file(k);
            part += ".part";
            std::filesystem::remove(file(k), ec), std::filesystem::remove(part, ec);
        }
    }

private:
    bool enabled_ = false, resume_ = false;
    long every_ = 0, stop_after_ = 0, steps_ = 0;
    int next_ = 0;
    std::filesystem::path out_;
    std::string fingerprint_;

    // The pieces of loop(): begin() loads the state and says where the loop starts; after_step()
    // after each step n; end() after the last.
    struct Resumed {
        int loop = 0;
        long step = 0;          // 0: from the start
        bool complete = false;  // the loop had ended: take no step
    };
    template <class State>
    Resumed begin(State&& state)
    {
        Resumed at{next_++};
        if (!enabled_) return at;
        OutputManifest::record(file(at.loop));  // a later new run into the folder removes it
        if (!resume_ || !std::filesystem::exists(file(at.loop))) return at;
        StateArchive ar = read(at.loop);
        try {
            ar("driver.step", at.step), ar("driver.complete", at.complete);
            state(ar);
        } catch (const std::invalid_argument& e) {
            throw std::invalid_argument("option --resume: " + std::string(e.what()));
        }
        return at;
    }
    template <class State>
    void after_step(const Resumed& at, long n, State&& state)
    {
        if (!enabled_) return;
        ++steps_;
        int sig = stop_signal;
        if (sig == 0 && stop_after_ > 0 && steps_ >= stop_after_) sig = SIGINT;
        if ((every_ > 0 && n % every_ == 0) || sig != 0) write(at.loop, n, false, state);
        if (sig == 0) return;
        stopping_to_resume() = true;  // the files still open keep their ".part" names (csv.hpp)
        throw Interrupted("stopped by " + std::string(signal_name(sig)) + (stop_signal == 0 ? " (--stop-after)" : "") + " after step " +
                              std::to_string(n) + " of time loop " + std::to_string(at.loop) + "; checkpoints in " + out_.string() +
                              " (continue with the same options and --resume)",
                          sig);
    }
    template <class State>
    void end(const Resumed& at, long n, State&& state)
    {
        if (enabled_) write(at.loop, n, true, state);
    }

    std::filesystem::path file(int k) const { return out_ / ("checkpoint_" + std::to_string(k) + ".pdstate"); }

    // The checkpoint of loop k, refused (std::invalid_argument naming --resume) when it is not a
    // checkpoint or one of a run with other options.
    StateArchive read(int k) const
    {
        try {
            StateArchive ar = StateArchive::read(file(k));
            std::string saved;
            ar("driver.options", saved);
            if (const std::string diff = first_difference(saved, fingerprint_); !diff.empty())
                throw std::invalid_argument("the checkpoints in '" + out_.string() + "' are of another run: " + diff);
            return ar;
        } catch (const std::invalid_argument& e) {
            throw std::invalid_argument("option --resume: " + std::string(e.what()));
        }
    }

    template <class State>
    void write(int k, long n, bool complete, State&& state) const
    {
        StateArchive ar;
        std::string options = fingerprint_;
        ar("driver.options", options);
        ar("driver.step", n), ar("driver.complete", complete);
        state(ar);
        ar.write(file(k));
    }
};

}  // namespace pd::io
