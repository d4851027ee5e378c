// Shared set-up of the heat-conduction tests.
#pragma once
#include "pd/core/lattice.hpp"

namespace pd_test {

// The cube [0, n dx]^D of n^D cells (measure: 1D area, 2D thickness).
template <int D>
pd::Body<D> cube(int n, double dx, double measure = 1)
{
    pd::Vec<D> lo{}, hi{};
    for (int d = 0; d < D; ++d) hi[d] = n * dx;
    return pd::box<D>(lo, hi, dx, measure);
}

}  // namespace pd_test
