// Shared set-up of the correspondence tests (test_correspondence.cpp, test_correspondence_damaged_pass.cpp,
// test_correspondence_flanagan_taylor.cpp): lattice spacing, horizon, steel, affine maps y = A x + c and
// random matrices near I.
#pragma once

#include "pd/models/correspondence.hpp"

#include <cstddef>
#include <random>

namespace pd_test::correspondence_fixtures {

using namespace pd;
using C3 = Correspondence<3>;
using M3 = C3::Mat;

inline constexpr double dx = 1e-3;        // lattice spacing [m]
inline constexpr double m_ratio = 3.05;   // delta / dx, the source's Peridigm value
inline const Elastic steel = Elastic::from_E_nu(200e9, 0.3);

template <int D>
Field<D> affine(const Body<D>& body, const Eigen::Matrix<double, D, D>& A, const Eigen::Matrix<double, D, 1>& c)
{
    Field<D> y(body.size());
    for (std::size_t i = 0; i < body.size(); ++i)
        for (int a = 0; a < D; ++a) {
            double s = c(a);
            for (int b = 0; b < D; ++b) s += A(a, b) * body.x.c[b][i];
            y.c[a][i] = s;
        }
    return y;
}

// I plus entries uniform in [-amplitude, amplitude].
inline M3 random_matrix(std::mt19937& gen, double amplitude)
{
    std::uniform_real_distribution<double> U(-amplitude, amplitude);
    M3 A;
    for (int a = 0; a < 3; ++a) for (int b = 0; b < 3; ++b) A(a, b) = (a == b) + U(gen);
    return A;
}

}  // namespace pd_test::correspondence_fixtures
