// parallel_for over nodes (OpenMP, static schedule). Owner computes: each iteration writes only
// node i, so results do not depend on the number of threads.
#pragma once
#include <cstddef>

namespace pd {

// Below this many nodes a loop runs serially: a parallel region costs microseconds (far more on
// an oversubscribed machine), more than a small 1D scene's whole step.
inline constexpr long parallel_min_nodes = 2048;

template <class Fn>
inline void parallel_for(std::size_t n, Fn&& fn)
{
    const long nn = static_cast<long>(n);
#pragma omp parallel for schedule(static) if (nn >= parallel_min_nodes)
    for (long i = 0; i < nn; ++i) fn(static_cast<std::size_t>(i));
}

// parallel_for over n work items (chunks, runs of chunks) that cover `nodes` nodes in all: the
// threshold counts nodes, not items. Uneven = true: dynamic schedule, for items of different sizes.
// Owner computes as above, so the schedule does not change the results.
template <bool Uneven = false, class Fn>
inline void parallel_for_items(std::size_t n, std::size_t nodes, Fn&& fn)
{
    const long nn = static_cast<long>(n);
    const bool par = static_cast<long>(nodes) >= parallel_min_nodes && nn > 1;
    if constexpr (Uneven) {
#pragma omp parallel for schedule(dynamic, 1) if (par)
        for (long i = 0; i < nn; ++i) fn(static_cast<std::size_t>(i));
    } else {
#pragma omp parallel for schedule(static) if (par)
        for (long i = 0; i < nn; ++i) fn(static_cast<std::size_t>(i));
    }
}

void set_threads(int threads);  // 0 keeps the OpenMP default
int max_threads();

}  // namespace pd
