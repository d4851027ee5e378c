// pd/damage/singular_nodes.hpp -- the thesis' rule for correspondence models with damage (Biondani
// 2018 sec. 8.3; spec/000c sec. 2.5): a node whose shape tensor became singular (K^-1 = 0, as
// Correspondence::inverse_or_zero sets it) or whose det F <= 0 loses all its bonds, since the
// forces of an ill-conditioned K or an inverted F grow without bound. Non-physical, but it lets
// fracture runs complete. For models that expose per-node Kinv and F (correspondence) or wrap one
// as `.model` (plastic, viscoelastic correspondence); other models have no such node: no-op.
// Usage (time/verlet.hpp with the critical-stretch rule; damage/micropotential.hpp in accumulate):
// mark_singular_nodes(model, n, detached) after a force evaluation, then break_detached_bonds
// before the next one. `detached` is sticky: once detached, a node stays so.
#pragma once
#include "pd/core/bonds.hpp"

#include <cstdint>
#include <vector>

namespace pd {

// Flags (in detached, sized n on first use) the nodes singular in the model's last point pass;
// returns how many were newly flagged.
template <class Model>
long mark_singular_nodes(const Model& model, std::size_t n, std::vector<std::uint8_t>& detached)
{
    if constexpr (requires { model.Kinv; model.F; }) {
        if (detached.size() != n) detached.assign(n, 0);
        long added = 0;
        for (std::size_t i = 0; i < n; ++i)
            if (!detached[i] && (model.Kinv[i].isZero(0.0) || !(model.F[i].determinant() > 0))) {
                detached[i] = 1;
                ++added;
            }
        return added;
    } else if constexpr (requires { model.model.Kinv; model.model.F; }) {
        return mark_singular_nodes(model.model, n, detached);
    } else {
        return 0;
    }
}

// Breaks every intact bond with a detached end, except bonds touching a no-fail node (empty: none);
// symmetric in i, j: both halves of each pair of a detached node at once, so only the detached
// nodes' families are read. Returns how many ordered bonds broke.
inline long break_detached_bonds(Bonds& b, const std::vector<std::uint8_t>& detached, const std::vector<std::uint8_t>& no_fail)
{
    long broken = 0;
    for (std::size_t i = 0; i < detached.size(); ++i) {
        if (!detached[i] || (!no_fail.empty() && no_fail[i])) continue;
        for_family(b, i, [&](std::int64_t k, int j) {
            if (no_fail.empty() || !no_fail[j]) broken += b.break_pair(k);
        });
    }
    return broken;
}

}  // namespace pd
