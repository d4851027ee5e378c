// pd/core/errors.hpp -- the error types of the library, below every layer so that any layer may throw
// them and io/guarded_main.hpp may map them to exit statuses without including an integrator.
//   Unstable: a run that became unstable (non-finite state, energy blow-up); names the step and
//   the node (exit status 3). Invalid scenes and inputs throw std::invalid_argument (status 2).
//   SolverFailure: an implicit solver could not continue the run (exit status 3, one line);
//   TimeScaleBeyondSolver: it could not even start on the input's time scale (status 2).
//   NonFiniteResult: a headline result of a finished run is nan or inf (exit status 3 too: the run's
//   numbers are not to be trusted, whether or not --check was given).
//   Interrupted: a stop signal ended the run after a checkpoint (exit status 128 + signal).
//   require_memory: a scene too large for this machine is refused before it is allocated (status 2).
//   require_steps: a run whose step count exceeds the step limit is refused before it loops (status 2).
#pragma once
#include <unistd.h>

#include <cstdio>
#include <stdexcept>
#include <string>

namespace pd {

struct Unstable : std::runtime_error {
    long step;  // the step at which the guard fired
    int node;   // the node named in the message (0 when the guard is global)
    Unstable(const std::string& what, long step, int node) : std::runtime_error(what), step(step), node(node) {}
};

// A solver (CVODE, Newton) that could not continue a run past some time; one line (status 3).
struct SolverFailure : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct NonFiniteResult : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A solver that cannot take its first step on the time scale the input sets (CVODE at t0): bad
// input, exit status 2, with the options that set that scale when the driver names them
// (io::Case::time_scale_set_by).
struct TimeScaleBeyondSolver : std::invalid_argument {
    using std::invalid_argument::invalid_argument;
};

// A run stopped by a signal (SIGINT, SIGTERM) after its checkpoint was written (io/checkpoints.hpp);
// exit status 128 + signal, the shell's convention for a run ended by that signal.
struct Interrupted : std::runtime_error {
    int signal;
    Interrupted(const std::string& what, int signal) : std::runtime_error(what), signal(signal) {}
};

// The machine's physical memory [bytes] (0 when unknown).
inline double physical_memory()
{
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) : 0.0;
}

// Throws std::invalid_argument when an estimated allocation of `bytes` for `what` (e.g. "a lattice
// of 1e12 cells") exceeds the physical memory: an oversized input then ends with one line and
// status 2 at once instead of allocating until bad_alloc (or the kernel's out-of-memory killer).
inline void require_memory(double bytes, const std::string& what)
{
    const double have = physical_memory();
    if (have > 0 && !(bytes <= have)) {
        char text[96];
        std::snprintf(text, sizeof text, " needs about %.3g GiB, more than the %.3g GiB of this machine", bytes / 1073741824.0,
                      have / 1073741824.0);
        throw std::invalid_argument(what + text);
    }
}

// The most time steps a run may take (drivers: --max-steps, set by io::Case; 0 = no limit). A run
// of 10^8 steps takes hours even on a small scene: beyond it an input (a huge end time, a tiny
// step) is far more likely a slip than a wish.
inline long& step_limit()
{
    static long limit = 100000000;
    return limit;
}

// Throws std::invalid_argument when a run needs more than step_limit() steps; `what` names the
// options that set the count (e.g. "--t-end / dt").
inline void require_steps(double steps, const std::string& what)
{
    if (step_limit() > 0 && !(steps <= static_cast<double>(step_limit()))) {
        char text[160];
        std::snprintf(text, sizeof text, " asks for %.3g time steps, more than the limit %ld (raise it with --max-steps, 0 = none)", steps,
                      step_limit());
        throw std::invalid_argument(what + text);
    }
}

}  // namespace pd
