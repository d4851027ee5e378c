// pd/core/errors.hpp -- the error types of the library, below every layer so that any layer may throw
// them and io/guarded_main.hpp may map them to exit statuses without including an integrator.
//   Unstable: a run that became unstable (non-finite state, energy blow-up); names the step and
//   the node (exit status 3). Invalid scenes and inputs throw std::invalid_argument (status 2).
#pragma once
#include <stdexcept>
#include <string>

namespace pd {

struct Unstable : std::runtime_error {
    long step;  // the step at which the guard fired
    int node;   // the node named in the message (0 when the guard is global)
    Unstable(const std::string& what, long step, int node) : std::runtime_error(what), step(step), node(node) {}
};

}  // namespace pd
