// Node positions under an affine map y = F x (the patch tests of test_models.cpp and
// test_model_constants.cpp).
#pragma once

#include "pd/core/field.hpp"
#include "pd/core/lattice.hpp"

#include <array>

namespace pd_test {

template <int D>
pd::Field<D> affine_positions(const pd::Body<D>& body, const std::array<std::array<double, D>, D>& F)
{
    pd::Field<D> y(body.size());
    for (std::size_t i = 0; i < body.size(); ++i)
        for (int a = 0; a < D; ++a) {
            double s = 0;
            for (int b = 0; b < D; ++b) s += F[a][b] * body.x.c[b][i];
            y.c[a][i] = s;
        }
    return y;
}

}  // namespace pd_test
