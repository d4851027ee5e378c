// Shared set-up of the PMB surface-correction tests (test_surface_correction.cpp,
// test_surface_correction_stiffness.cpp): the uniaxial strain y = x + eps x_a e_a.
#pragma once

#include "pd/core/lattice.hpp"

#include <cstddef>

namespace pd_test::surface_correction_fixtures {

using namespace pd;

// y = x + eps x_a e_a (uniaxial strain along a), written here independently of the library.
template <int D>
Field<D> uniaxial(const Body<D>& body, int a, double eps)
{
    Field<D> y = body.x;
    for (std::size_t i = 0; i < body.size(); ++i) y.c[a][i] += eps * body.x.c[a][i];
    return y;
}

}  // namespace pd_test::surface_correction_fixtures
