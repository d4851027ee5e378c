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

void set_threads(int threads);  // 0 keeps the OpenMP default
int max_threads();

}  // namespace pd
