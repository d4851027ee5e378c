// pd/io/guarded_main.hpp -- the exit-status contract of every executable, in one place:
//   0 done, 1 a --check failed (the driver returns it), 2 invalid input (one line naming it),
//   3 the run became unstable (step and node named; files written so far are kept) or ended with a
//     non-finite headline result (the quantity named; summary.csv is written first) or a solver
//     could not continue it (SolverFailure);
//   128 + signal: SIGINT or SIGTERM stopped the run after writing its checkpoint (io/checkpoints.hpp).
// Library calls reject impossible scenes with std::invalid_argument (empty node set, lattice
// thinner than a cell, dx <= 0, ...); here they become the one-line message and status 2.
//
//     int main(int argc, char** argv) { return pd::io::guarded_main("bar_modes_1d", [&] { return run(argc, argv); }); }
#pragma once

#include "pd/core/errors.hpp"

#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

namespace pd::io {

// The options that set the time scale of a driver's problem (Case::time_scale_set_by), named when a
// solver cannot take its first step on it (pd::TimeScaleBeyondSolver).
inline std::string& time_scale_options()
{
    static std::string options;
    return options;
}

template <class Fn>
int guarded_main(const char* program, Fn&& fn)
{
    try {
        return fn();
    } catch (const Unstable& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return 3;
    } catch (const SolverFailure& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return 3;
    } catch (const NonFiniteResult& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return 3;
    } catch (const Interrupted& e) {
        std::fprintf(stderr, "%s: %s\n", program, e.what());
        return 128 + e.signal;
    } catch (const TimeScaleBeyondSolver& e) {
        const std::string& o = time_scale_options();
        std::fprintf(stderr, "%s: error: %s%s\n", program, o.empty() ? "" : ("options " + o + ": ").c_str(), e.what());
        return 2;
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "%s: error: %s\n", program, e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: failed: %s\n", program, e.what());
        return 1;
    }
}

}  // namespace pd::io
