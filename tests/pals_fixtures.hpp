// Shared set-up of the PALS tests (test_pals.cpp, test_pals_consistency.cpp): the affine map
// y = x + h H x and the steel of both.
#pragma once

#include "pd/core/lattice.hpp"
#include "pd/core/material.hpp"

#include <array>
#include <cstddef>

namespace pd_test::pals_fixtures {

using namespace pd;

using Mat3 = std::array<std::array<double, 3>, 3>;

// y = x + h H x.
inline Field<3> affine(const Body<3>& body, const Mat3& H, double h)
{
    Field<3> y(body.size());
    for (std::size_t i = 0; i < body.size(); ++i)
        for (int a = 0; a < 3; ++a) {
            double s = body.x.c[a][i];
            for (int b = 0; b < 3; ++b) s += h * H[a][b] * body.x.c[b][i];
            y.c[a][i] = s;
        }
    return y;
}

inline const Elastic steel = Elastic::from_E_nu(200e9, 0.3);

}  // namespace pd_test::pals_fixtures
