// parallel_for over nodes (OpenMP, static schedule). Owner computes: each iteration writes only
// node i, so results do not depend on the number of threads.
#pragma once
#include <cstddef>

namespace pd {

template <class Fn>
inline void parallel_for(std::size_t n, Fn&& fn)
{
    const long nn = static_cast<long>(n);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < nn; ++i) fn(static_cast<std::size_t>(i));
}

void set_threads(int threads);  // 0 keeps the OpenMP default
int max_threads();

}  // namespace pd
